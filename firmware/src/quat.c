#include "fw/quat.h"

static void normalize(tse_real q[4])
{
    const tse_real n = tse_sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    for (int k = 0; k < 4; ++k)
        q[k] /= n;
}

void fw_quat_from_rpy(tse_real roll, tse_real pitch, tse_real yaw, tse_real q[4])
{
    const tse_real cr = tse_cos(TSE_R(0.5) * roll), sr = tse_sin(TSE_R(0.5) * roll);
    const tse_real cp = tse_cos(TSE_R(0.5) * pitch), sp = tse_sin(TSE_R(0.5) * pitch);
    const tse_real cy = tse_cos(TSE_R(0.5) * yaw), sy = tse_sin(TSE_R(0.5) * yaw);
    /* qz(yaw) * qy(pitch) * qx(roll) */
    q[0] = cy * cp * cr + sy * sp * sr;
    q[1] = cy * cp * sr - sy * sp * cr;
    q[2] = cy * sp * cr + sy * cp * sr;
    q[3] = sy * cp * cr - cy * sp * sr;
}

void fw_quat_to_rpy(const tse_real q[4], tse_real rpy[3])
{
    const tse_real w = q[0], x = q[1], y = q[2], z = q[3];
    /* Elements of R = Rz Ry Rx: R20 = -sin(pitch), R21 = cos(pitch) sin(roll), ... */
    const tse_real r20 = TSE_R(2.0) * (x * z - w * y);
    const tse_real r21 = TSE_R(2.0) * (y * z + w * x);
    const tse_real r22 = TSE_R(1.0) - TSE_R(2.0) * (x * x + y * y);
    const tse_real r10 = TSE_R(2.0) * (x * y + w * z);
    const tse_real r00 = TSE_R(1.0) - TSE_R(2.0) * (y * y + z * z);
    tse_real s = -r20;
    if (s > TSE_R(1.0))
        s = TSE_R(1.0);
    if (s < TSE_R(-1.0))
        s = TSE_R(-1.0);
    rpy[0] = tse_atan2(r21, r22);
    rpy[1] = tse_asin(s);
    rpy[2] = tse_atan2(r10, r00);
}

static tse_real dot(const tse_real a[4], const tse_real b[4])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
}

tse_real fw_quat_angle(const tse_real a[4], const tse_real b[4])
{
    /* 2 acos(d) loses half the digits near d = 1; the half-angle's sine does not. */
    tse_real diff[4];
    const tse_real sgn = dot(a, b) < TSE_R(0.0) ? TSE_R(-1.0) : TSE_R(1.0);
    for (int k = 0; k < 4; ++k)
        diff[k] = b[k] * sgn - a[k];
    const tse_real chord = tse_sqrt(dot(diff, diff)); /* = 2 sin(angle / 4) */
    return TSE_R(4.0) * tse_asin(TSE_R(0.5) * chord);
}

void fw_quat_slerp(const tse_real a[4], const tse_real b[4], tse_real u, tse_real out[4])
{
    tse_real bb[4];
    const tse_real sgn = dot(a, b) < TSE_R(0.0) ? TSE_R(-1.0) : TSE_R(1.0);
    for (int k = 0; k < 4; ++k)
        bb[k] = sgn * b[k];
    const tse_real theta = TSE_R(0.5) * fw_quat_angle(a, b); /* half the rotation angle */
    if (theta < TSE_R(1e-4)) {
        /* Nearly equal: the sines below would lose everything; lerp is exact to O(theta^3). */
        for (int k = 0; k < 4; ++k)
            out[k] = a[k] + u * (bb[k] - a[k]);
    } else {
        const tse_real s = tse_sin(theta);
        const tse_real wa = tse_sin((TSE_R(1.0) - u) * theta) / s;
        const tse_real wb = tse_sin(u * theta) / s;
        for (int k = 0; k < 4; ++k)
            out[k] = wa * a[k] + wb * bb[k];
    }
    normalize(out);
}

void fw_quat_mul(const tse_real b[4], const tse_real a[4], tse_real out[4])
{
    const tse_real w = b[0] * a[0] - b[1] * a[1] - b[2] * a[2] - b[3] * a[3];
    const tse_real x = b[0] * a[1] + b[1] * a[0] + b[2] * a[3] - b[3] * a[2];
    const tse_real y = b[0] * a[2] - b[1] * a[3] + b[2] * a[0] + b[3] * a[1];
    const tse_real z = b[0] * a[3] + b[1] * a[2] - b[2] * a[1] + b[3] * a[0];
    out[0] = w;
    out[1] = x;
    out[2] = y;
    out[3] = z;
}

void fw_quat_conj(const tse_real a[4], tse_real out[4])
{
    out[0] = a[0];
    out[1] = -a[1];
    out[2] = -a[2];
    out[3] = -a[3];
}
