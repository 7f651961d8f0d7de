#include "kin_internal.h"
#include "tse/ik.h"
#include "tse/jacobian.h"

/* The per-scissor checks of kinematics.md, in its order, on a branch solution. */
static tse_status check_scissor(const tse_geometry *g, const tse_real C[3], const tse_scissor_solution *s)
{
    if (!(C[2] > TSE_R(0.0)))
        return TSE_BELOW;
    /* w_hi = 2 l0 cos(alpha_min) < 2 l0, so this band also enforces w <= 2 l0. */
    if (!(s->w >= g->w_lo && s->w <= g->w_hi))
        return TSE_ALPHA;
    if (!(s->s_a >= g->p.s_min && s->s_a <= g->p.s_max && s->s_b >= g->p.s_min && s->s_b <= g->p.s_max))
        return TSE_STROKE;
    if (!(s->mu >= g->p.mu_min))
        return TSE_SINGULAR;
    return TSE_OK;
}

static tse_status reject(tse_ik_result *out, tse_status st, int scissor)
{
    out->status = st;
    out->scissor = scissor;
    return st;
}

/* Whether every x[k] is finite: x * 0 is 0 for a finite x and NaN for an infinity or a NaN, and
 * a sum of zeros stays zero.  One multiply-add per value instead of a test and a branch. */
static int all_finite(const tse_real *x, int n)
{
    tse_real z = TSE_R(0.0);
    for (int k = 0; k < n; ++k)
        z += x[k] * TSE_R(0.0);
    return z == TSE_R(0.0);
}

tse_status tse_ik(const tse_geometry *g, const tse_real pose[6], const tse_real seed_q[6],
                  tse_ik_result *out)
{
    out->status = TSE_OK;
    out->scissor = 0;
    out->nu = (tse_real)NAN;
    out->iterations = 0;
    out->fallbacks = 0;

    /* A non-finite pose or seed reaches every scissor: the first failing one is scissor 1. */
    if (!all_finite(pose, 6) || (seed_q != NULL && !all_finite(seed_q, 6))) {
        for (int k = 0; k < 6; ++k)
            out->q[k] = (tse_real)NAN;
        for (int i = 0; i < 3; ++i) {
            out->mu[i] = (tse_real)NAN;
            for (int k = 0; k < 3; ++k)
                out->C[i][k] = (tse_real)NAN;
        }
        return reject(out, TSE_INVALID, 1);
    }

    /* A finite pose gives finite ball joints (|r_top R e| <= r_top), so the solver's own checks
     * of its input are skipped. */
    tse_plate frame;
    tse_plate_frame(pose, &frame);
    tse_apex_from_frame(g, pose, &frame, out->C);

    /* All three are solved even after a failure, so that a rejection still shows every slide. */
    tse_status first = TSE_OK;
    int first_scissor = 0;
    tse_scissor_local loc[3];
    for (int i = 0; i < 3; ++i) {
        tse_scissor_solution sol;
        const tse_real seed_a = seed_q ? seed_q[2 * i] : g->home_s;
        const tse_real seed_b = seed_q ? seed_q[2 * i + 1] : g->home_s;
        tse_scissor_localize(g, i, out->C[i], &loc[i]);
        tse_status st = tse_scissor_solve_local(g, &loc[i], seed_a, seed_b, &sol);
        out->iterations += sol.iterations;
        out->fallbacks += sol.fallback;
        if (st == TSE_OK) {
            out->q[2 * i] = sol.s_a;
            out->q[2 * i + 1] = sol.s_b;
            out->mu[i] = sol.mu;
            st = check_scissor(g, out->C[i], &sol);
        } else {
            out->q[2 * i] = (tse_real)NAN;
            out->q[2 * i + 1] = (tse_real)NAN;
            out->mu[i] = (tse_real)NAN;
        }
        if (st != TSE_OK && first == TSE_OK) {
            first = st;
            first_scissor = i + 1;
        }
    }
    if (first != TSE_OK)
        return reject(out, first, first_scissor);

    /* Type 2: rotation columns in metres of ball-joint travel, so that they weigh like the
     * translation columns whatever the plate size. */
    out->nu = tse_type2_margin(g, pose, &frame, out->C, loc, out->q);
    if (!(out->nu >= g->p.nu_min)) {
        tse_real Fp[6][6];
        tse_constraint_rows(g, pose, &frame, out->C, out->q, g->inv_r_top, Fp, NULL);
        const int row = tse_weakest_row6(Fp);
        return reject(out, TSE_DEGENERATE, row < 0 ? 1 : row / 2 + 1);
    }
    return TSE_OK;
}
