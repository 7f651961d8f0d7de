/* One scissor: the branch solution of F1 = F2 = 0 for a given ball joint.  The Newton solver
 * itself is in scissor_core.h. */
#include "scissor_core.h"
#include "tse/ik.h"

enum { POLISH_MAX_ITER = 8 };

void tse_scissor_localize(const tse_geometry *g, int i, const tse_real C[3], tse_scissor_local *loc)
{
    scissor_localize_inline(&g->sc[i], C, loc);
}

void tse_newton_limits(tse_geometry *g)
{
    const tse_real L2 = g->p.L * g->p.L;
    g->L2 = L2;
    /* acc = 1e-4 sqrt(eps) L and the quadratic regime's 1e-3 L, squared. */
    g->newton_acc2 = TSE_R(1e-8) * TSE_REAL_EPS * L2;
    g->newton_regime2 = TSE_R(1e-6) * L2;
    g->newton_max2 = g->step_max * g->step_max;
}

void tse_scissor_eval(const tse_geometry *g, const tse_scissor_local *loc, tse_real s_a, tse_real s_b,
                      tse_real F[2], tse_real M[2][2])
{
    scissor_consts k;
    scissor_point pt;
    scissor_consts_of(g, loc, &k);
    scissor_eval_point(&k, s_a, s_b, &pt);
    F[0] = pt.F1;
    F[1] = pt.F2;
    M[0][0] = TSE_R(2.0) * pt.ea;
    M[0][1] = TSE_R(-2.0) * pt.eb;
    M[1][0] = TSE_R(2.0) * pt.m21;
    M[1][1] = TSE_R(2.0) * pt.m22;
}

void tse_scissor_residual(const tse_geometry *g, int i, const tse_real C[3], tse_real s_a,
                          tse_real s_b, tse_real F[2])
{
    tse_scissor_local loc;
    tse_real M[2][2];
    tse_scissor_localize(g, i, C, &loc);
    tse_scissor_eval(g, &loc, s_a, s_b, F, M);
}

/* Every solution, from the real roots of the quartic 4 m^2 F2 = 0 in m = (s_A - u) + (s_B - v)
 * (kinematics.md, solver notes); each root is polished by Newton on the original pair.  Keeps the
 * physical one that is inside the limits if any, then the one nearest the seed. */
static int enumerate(const tse_geometry *g, const scissor_consts *k, const tse_scissor_local *loc,
                     tse_real seed_a, tse_real seed_b, tse_scissor_solution *best, int *iterations)
{
    const tse_real u = loc->u, v = loc->v, ga = g->g, c = g->c, L = g->p.L;
    const tse_real delta = u * u - v * v;
    /* P = m^2 + 2u m + delta = 2 m s_A,  Q = m^2 + 2v m - delta = 2 m s_B. */
    const tse_real P[3] = {delta, TSE_R(2.0) * u, TSE_R(1.0)};
    const tse_real Q[3] = {-delta, TSE_R(2.0) * v, TSE_R(1.0)};
    const tse_real K = loc->rho2 - L * L - u * u;
    tse_real coef[5] = {delta * delta, TSE_R(0.0), TSE_R(2.0) * delta + TSE_R(4.0) * K, TSE_R(0.0),
                        TSE_R(1.0)};
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
            const tse_real w = P[i] * P[j] + Q[i] * Q[j] + TSE_R(2.0) * c * P[i] * Q[j];
            coef[i + j] -= ga * w;
        }
    }
    tse_real roots[4];
    const int n = tse_poly_real_roots(coef, 4, roots);
    int found = 0, best_in = 0;
    tse_real best_dist = TSE_R(0.0);
    for (int r = 0; r < n; ++r) {
        const tse_real m = roots[r];
        if (m == TSE_R(0.0))
            continue;
        tse_real a = (m * m + TSE_R(2.0) * u * m + delta) / (TSE_R(2.0) * m);
        tse_real b = (m * m + TSE_R(2.0) * v * m - delta) / (TSE_R(2.0) * m);
        /* The root came from a squared-up polynomial: polish it on the equations themselves. */
        tse_scissor_solution cand;
        int valid = scissor_newton(g, k, loc->rho2, &a, &b, POLISH_MAX_ITER, 0, iterations, &cand);
        if (valid < 0)
            valid = scissor_describe_at(g, k, loc->rho2, a, b, 0, &cand);
        /* A polish that wandered off a spurious root leaves a residual far above rounding. */
        if (!valid)
            continue;
        const int in = scissor_within_limits(g, &cand);
        const tse_real dist = (a - seed_a) * (a - seed_a) + (b - seed_b) * (b - seed_b);
        if (!found || (in && !best_in) || (in == best_in && dist < best_dist)) {
            *best = cand;
            best_in = in;
            best_dist = dist;
            found = 1;
        }
    }
    return found;
}

tse_status tse_scissor_fallback(const tse_geometry *g, const tse_scissor_local *loc, tse_real seed_a,
                                tse_real seed_b, tse_real s_a, tse_real s_b, int iterations,
                                tse_scissor_solution *out)
{
    /* Newton stalled, left the sheet, or found a solution outside the limits while another might
     * be inside them: only the full enumeration can tell. */
    scissor_consts k;
    scissor_consts_of(g, loc, &k);
    tse_scissor_solution best;
    /* Beyond the reach (geometry.h) the quartic's terms can overflow into a false root. */
    const int found = loc->rho2 <= g->reach2 && enumerate(g, &k, loc, seed_a, seed_b, &best, &iterations);
    if (found) {
        *out = best;
    } else {
        /* Leave something printable for diagnostics. */
        scissor_describe_at(g, &k, loc->rho2, s_a, s_b, 0, out);
    }
    out->iterations = iterations;
    out->fallback = 1;
    return found ? TSE_OK : TSE_UNREACHABLE;
}

tse_status tse_scissor_solve_local(const tse_geometry *g, const tse_scissor_local *loc,
                                   tse_real seed_a, tse_real seed_b, tse_scissor_solution *out)
{
    tse_real a = seed_a, b = seed_b;
    int iterations;
    if (scissor_solve_fast(g, loc, &a, &b, 0, &iterations, out))
        return TSE_OK;
    return tse_scissor_fallback(g, loc, seed_a, seed_b, a, b, iterations, out);
}

tse_status tse_scissor_solve(const tse_geometry *g, int i, const tse_real C[3], tse_real seed_a,
                             tse_real seed_b, tse_scissor_solution *out)
{
    out->iterations = 0;
    out->fallback = 0;
    if (!isfinite(C[0]) || !isfinite(C[1]) || !isfinite(C[2]) || !isfinite(seed_a) || !isfinite(seed_b))
        return TSE_INVALID;
    tse_scissor_local loc;
    tse_scissor_localize(g, i, C, &loc);
    return tse_scissor_solve_local(g, &loc, seed_a, seed_b, out);
}
