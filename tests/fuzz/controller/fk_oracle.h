/* The plate pose of a set of slides by the double-precision kinematics, whatever precision the
 * controller under test is built in (this library is compiled in double on its own): the oracle
 * for the pose the controller reports from its slides (FK_A..C) and for the slides being at a
 * pose at all.  Plain doubles at the interface, so a float build of the controller can call it. */
#ifndef FUZZ_CONTROLLER_FK_ORACLE_H
#define FUZZ_CONTROLLER_FK_ORACLE_H

#include <stdint.h>

/* The kinematic parameters in the firmware's units (millionths of m, rad or of the ratio), in the
 * order of tse_params: L, k1, eta, k3, k4, alpha_min, alpha_max, s_min, s_max, mu_min, nu_min. */
#define FK_ORACLE_PARAMS 11

/* The pose [m, rad] whose slides are q [m], by Newton from seed (a pose near it); 0 when found
 * (the inverse kinematics reproduces q), else the kinematics' status.  *q_error: the largest
 * |IK(pose) - q| [m]. */
int fk_oracle_pose(const int64_t kin_micro[FK_ORACLE_PARAMS], const double q[6], const double seed[6],
                   double pose[6], double *q_error);

/* The slides [m] of pose [m, rad] on the physical branch nearest seed_q, by the double-precision
 * inverse kinematics with no limit checked (a pose at or past a margin has slides too); 0 when
 * every scissor has a solution. */
int fk_oracle_slides(const int64_t kin_micro[FK_ORACLE_PARAMS], const double pose[6], const double seed_q[6],
                     double q[6]);

#endif
