#include "kin_internal.h"
#include "tse/fk.h"
#include "tse/ik.h"

enum { FK_MAX_ITER = 60 };

static tse_status fail(tse_fk_result *out, tse_status st, int scissor)
{
    out->status = st;
    out->scissor = scissor;
    return st;
}

tse_status tse_fk(const tse_geometry *g, const tse_real q[6], const tse_real seed_pose[6],
                  tse_fk_result *out)
{
    out->status = TSE_OK;
    out->scissor = 0;
    out->iterations = 0;
    out->q_error = (tse_real)NAN;
    const tse_real *seed = seed_pose ? seed_pose : g->home_pose;
    for (int k = 0; k < 6; ++k) {
        out->pose[k] = seed[k];
        if (!isfinite(q[k]) || !isfinite(seed[k]))
            return fail(out, TSE_INVALID, 0);
    }
    /* Slides outside the stroke have no accepted pose, whatever Newton would make of them; said
     * before solving, since that search can end anywhere (no pose at all, or one the check then
     * refuses for another reason). */
    for (int k = 0; k < 6; ++k)
        if (!(q[k] >= g->p.s_min && q[k] <= g->p.s_max))
            return fail(out, TSE_STROKE, k / 2 + 1);
    /* Far from zero an angle is coarse (a float step is 1.2e-4 rad at 2000 rad, 2.5e-5 m of
     * ball-joint travel): Newton could not place the plate as finely as the slides need, and the
     * check below would pass a pose up to its tolerance off.  Same orientation, fine angles. */
    for (int k = TSE_ROLL; k <= TSE_YAW; ++k)
        if (tse_fabs(out->pose[k]) > TSE_R(2.0) * TSE_PI)
            out->pose[k] = tse_atan2(tse_sin(out->pose[k]), tse_cos(out->pose[k]));

    /* Same stopping rule as the per-scissor Newton: after a step this small the quadratic
     * error left is below what the precision resolves. */
    const tse_real tol = TSE_R(0.1) * tse_sqrt(TSE_REAL_EPS) * g->p.L;
    const tse_real max_move = TSE_R(0.1) * g->p.L;
    tse_real *p = out->pose;
    int converged = 0;
    for (int it = 1; it <= FK_MAX_ITER && !converged; ++it) {
        tse_plate frame;
        tse_real C[3][3], Fp[6][6], F[6], dp[6];
        int perm[6];
        tse_plate_frame(p, &frame);
        tse_apex_from_frame(g, p, &frame, C);
        for (int i = 0; i < 3; ++i)
            tse_scissor_residual(g, i, C[i], q[2 * i], q[2 * i + 1], &F[2 * i]);
        tse_constraint_rows(g, p, &frame, C, q, TSE_R(1.0), Fp, NULL);
        if (tse_lu_factor6(Fp, perm) == TSE_R(0.0))
            break;
        tse_lu_solve6(Fp, perm, F, dp);
        /* Length of the step in metres: the rotation moves the ball joints by r_top per radian. */
        tse_real n = TSE_R(0.0);
        for (int k = 0; k < 3; ++k)
            n += dp[k] * dp[k] + g->r_top * g->r_top * dp[3 + k] * dp[3 + k];
        n = tse_sqrt(n);
        if (!isfinite(n))
            break;
        const tse_real scale = n > max_move ? max_move / n : TSE_R(1.0);
        for (int k = 0; k < 6; ++k)
            p[k] -= scale * dp[k];
        out->iterations = it;
        converged = n <= tol;
    }
    if (!converged)
        return fail(out, TSE_NOCONVERGE, 0);

    /* The pose is only an answer if the inverse kinematics takes it back to q. */
    tse_ik_result ik;
    tse_ik(g, p, q, &ik);
    tse_real err = TSE_R(0.0);
    int worst = 0;
    for (int k = 0; k < 6; ++k) {
        const tse_real e = tse_fabs(ik.q[k] - q[k]);
        if (!(e <= err)) {
            err = e;
            worst = k / 2 + 1;
        }
    }
    out->q_error = err;
    if (ik.status != TSE_OK)
        return fail(out, ik.status, ik.scissor);
    const tse_real verify_tol = TSE_R(0.01) * tse_sqrt(TSE_REAL_EPS) * g->p.L;
    /* Converged to a pose whose physical configuration is not q: q is on another sheet. */
    if (!(err <= verify_tol))
        return fail(out, TSE_UNREACHABLE, worst);
    return TSE_OK;
}
