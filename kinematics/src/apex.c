#include "kin_internal.h"
#include "tse/ik.h"

void tse_plate_frame(const tse_real pose[6], tse_plate *f)
{
    tse_real sr, cr, sp, cp, sy, cy;
    tse_sincos(pose[TSE_ROLL], &sr, &cr);
    tse_sincos(pose[TSE_PITCH], &sp, &cp);
    tse_sincos(pose[TSE_YAW], &sy, &cy);
    tse_real(*R)[3] = f->R;
    R[0][0] = cy * cp;
    R[0][1] = cy * sp * sr - sy * cr;
    R[0][2] = cy * sp * cr + sy * sr;
    R[1][0] = sy * cp;
    R[1][1] = sy * sp * sr + cy * cr;
    R[1][2] = sy * sp * cr - cy * sr;
    R[2][0] = -sp;
    R[2][1] = cp * sr;
    R[2][2] = cp * cr;
    /* Roll turns about Rz Ry e_x (R's first column), pitch about Rz e_y, yaw about e_z. */
    for (int k = 0; k < 3; ++k)
        f->axes[0][k] = R[k][0];
    f->axes[1][0] = -sy;
    f->axes[1][1] = cy;
    f->axes[1][2] = TSE_R(0.0);
    f->axes[2][0] = TSE_R(0.0);
    f->axes[2][1] = TSE_R(0.0);
    f->axes[2][2] = TSE_R(1.0);
}

void tse_rotation(tse_real roll, tse_real pitch, tse_real yaw, tse_real R[3][3])
{
    const tse_real pose[6] = {TSE_R(0.0), TSE_R(0.0), TSE_R(0.0), roll, pitch, yaw};
    tse_plate f;
    tse_plate_frame(pose, &f);
    for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k)
            R[i][k] = f.R[i][k];
}

void tse_apex_from_frame(const tse_geometry *g, const tse_real pose[6], const tse_plate *f,
                         tse_real C[3][3])
{
    for (int i = 0; i < 3; ++i) {
        /* The ball joint sits on the plate at the scissor's own azimuth: e_r in plate axes. */
        const tse_real cx = g->sc[i].er[0], cy = g->sc[i].er[1];
        for (int k = 0; k < 3; ++k)
            C[i][k] = pose[k] + g->r_top * (f->R[k][0] * cx + f->R[k][1] * cy);
    }
}

void tse_apex_points(const tse_geometry *g, const tse_real pose[6], tse_real C[3][3])
{
    tse_plate f;
    tse_plate_frame(pose, &f);
    tse_apex_from_frame(g, pose, &f, C);
}
