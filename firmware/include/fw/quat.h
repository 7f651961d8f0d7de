/* Unit quaternions (w, x, y, z) for interpolating the plate's orientation: slerp moves at a
 * constant angular rate about one axis, with none of the detours or gimbal-lock surprises of
 * interpolating roll, pitch and yaw. */
#ifndef FW_QUAT_H
#define FW_QUAT_H

#include "tse/real.h"

/* The rotation Rz(yaw) Ry(pitch) Rx(roll) of kinematics.md. */
void fw_quat_from_rpy(tse_real roll, tse_real pitch, tse_real yaw, tse_real q[4]);

/* Back to roll, pitch, yaw, with pitch in [-pi/2, pi/2] and roll, yaw in (-pi, pi]. */
void fw_quat_to_rpy(const tse_real q[4], tse_real rpy[3]);

/* Angle of the rotation from a to b, in [0, pi]. */
tse_real fw_quat_angle(const tse_real a[4], const tse_real b[4]);

/* Along the shortest arc from a (u = 0) to b (u = 1). */
void fw_quat_slerp(const tse_real a[4], const tse_real b[4], tse_real u, tse_real out[4]);

/* The rotation a then b (b * a), and the inverse of a unit quaternion. */
void fw_quat_mul(const tse_real b[4], const tse_real a[4], tse_real out[4]);
void fw_quat_conj(const tse_real a[4], tse_real out[4]);

#endif
