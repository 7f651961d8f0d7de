/* One scissor: the branch solution of F1 = F2 = 0 for a given ball joint. */
#include "kin_internal.h"
#include "tse/ik.h"

enum { NEWTON_MAX_ITER = 40, POLISH_MAX_ITER = 8 };

void tse_scissor_localize(const tse_geometry *g, int i, const tse_real C[3], tse_scissor_local *loc)
{
    const tse_scissor_frame *f = &g->sc[i];
    loc->d[0] = C[0] - f->o[0];
    loc->d[1] = C[1] - f->o[1];
    loc->d[2] = C[2];
    loc->u = loc->d[0] * f->a[0] + loc->d[1] * f->a[1];
    loc->v = loc->d[0] * f->b[0] + loc->d[1] * f->b[1];
    loc->rho2 = loc->d[0] * loc->d[0] + loc->d[1] * loc->d[1] + loc->d[2] * loc->d[2];
}

void tse_scissor_eval(const tse_geometry *g, const tse_scissor_local *loc, tse_real s_a, tse_real s_b,
                      tse_real F[2], tse_real M[2][2])
{
    const tse_real ga = g->g, c = g->c, L = g->p.L;
    const tse_real ea = s_a - loc->u, eb = s_b - loc->v;
    /* |AC|^2 - |BC|^2 and |AC|^2 - L^2 - g |AB|^2, in the spec's polynomial form. */
    const tse_real ac2 = s_a * (s_a - TSE_R(2.0) * loc->u) + loc->rho2;
    const tse_real w2 = s_a * s_a + s_b * s_b + TSE_R(2.0) * c * s_a * s_b;
    F[0] = s_a * (s_a - TSE_R(2.0) * loc->u) - s_b * (s_b - TSE_R(2.0) * loc->v);
    F[1] = (ac2 - L * L) - ga * w2;
    M[0][0] = TSE_R(2.0) * ea;
    M[0][1] = TSE_R(-2.0) * eb;
    M[1][0] = TSE_R(2.0) * ea - TSE_R(2.0) * ga * (s_a + c * s_b);
    M[1][1] = TSE_R(-2.0) * ga * (s_b + c * s_a);
}

void tse_scissor_residual(const tse_geometry *g, int i, const tse_real C[3], tse_real s_a,
                          tse_real s_b, tse_real F[2])
{
    tse_scissor_local loc;
    tse_real M[2][2];
    tse_scissor_localize(g, i, C, &loc);
    tse_scissor_eval(g, &loc, s_a, s_b, F, M);
}

/* Newton from (s_a, s_b) with steps bounded by step_max.  It stops once a step n is below
 * sqrt(1e-3 eps) L: the error left, K n^2, is then below eps L for any curvature K up to 1e3 / L
 * (8e-10 m in double; 1.9e-5 m in float, still well above float's rounding floor of ~3e-7 m);
 * or earlier, once two successive steps show quadratic convergence and predict an error
 * (n_k^3 / n_{k-1}^2) below 1e-4 sqrt(eps) L (2.6e-12 m in double): a warm start then needs two
 * steps, not three.  That estimate of the curvature (n_k / n_{k-1}^2) only holds in the quadratic
 * regime, so it is trusted only after a step n_{k-1} below 1e-3 L: a large first step from a cold
 * seed lands anywhere, and its successor says nothing of the curvature.  A small step is not proof of a root (it can stall where |F| has a minimum),
 * so the caller checks the residual.  Returns 1 on convergence. */
static int newton(const tse_geometry *g, const tse_scissor_local *loc, tse_real *s_a, tse_real *s_b,
                  int max_iter, int *iterations)
{
    /* Compared as squares: the hot loop takes no square root unless a step must be clipped. */
    const tse_real tol = tse_sqrt(TSE_R(1e-3) * TSE_REAL_EPS) * g->p.L;
    const tse_real tol_final = TSE_R(1e-4) * tse_sqrt(TSE_REAL_EPS) * g->p.L;
    const tse_real tol2 = tol * tol, tol_final2 = tol_final * tol_final;
    const tse_real max2 = g->step_max * g->step_max;
    const tse_real regime2 = TSE_R(1e-6) * g->p.L * g->p.L;
    tse_real a = *s_a, b = *s_b, prev2 = TSE_R(0.0);
    for (int it = 1; it <= max_iter; ++it) {
        tse_real F[2], M[2][2];
        tse_scissor_eval(g, loc, a, b, F, M);
        const tse_real det = M[0][0] * M[1][1] - M[0][1] * M[1][0];
        if (!(tse_fabs(det) > TSE_R(0.0)) || !isfinite(det))
            break;
        const tse_real inv = TSE_R(1.0) / det;
        tse_real da = (M[1][1] * F[0] - M[0][1] * F[1]) * inv;
        tse_real db = (M[0][0] * F[1] - M[1][0] * F[0]) * inv;
        const tse_real n2 = da * da + db * db;
        if (!isfinite(n2))
            break;
        if (n2 > max2) {
            const tse_real k = g->step_max / tse_sqrt(n2);
            da *= k;
            db *= k;
        }
        a -= da;
        b -= db;
        *iterations += 1;
        /* n_k <= n_{k-1} / 4 and n_k^3 <= tol_final n_{k-1}^2, squared. */
        const int quadratic = it > 1 && prev2 <= regime2 && TSE_R(16.0) * n2 <= prev2 &&
                              n2 * n2 * n2 <= tol_final2 * prev2 * prev2;
        if (n2 <= tol2 || quadratic) {
            *s_a = a;
            *s_b = b;
            return 1;
        }
        prev2 = n2;
    }
    return 0;
}

/* Fills everything but the iteration counts from one evaluation at (s_a, s_b), and returns 1
 * when the point solves the pair and lies on the physical sheet (det M > 0, positive slides).
 *
 * Solves: a stalled iteration leaves |F| of 1e-2 and more, a root at most the stopping error
 * times |M| plus rounding; sqrt(eps) of the size of F's terms lies well between (9e-8 in double,
 * 2e-3 in float). */
static int describe(const tse_geometry *g, const tse_scissor_local *loc, tse_real s_a, tse_real s_b,
                    tse_scissor_solution *out)
{
    tse_real F[2], M[2][2];
    tse_scissor_eval(g, loc, s_a, s_b, F, M);
    out->s_a = s_a;
    out->s_b = s_b;
    out->det = M[0][0] * M[1][1] - M[0][1] * M[1][0];
    const tse_real n1 = M[0][0] * M[0][0] + M[0][1] * M[0][1];
    const tse_real n2 = M[1][0] * M[1][0] + M[1][1] * M[1][1];
    out->mu = out->det / tse_sqrt(n1 * n2);
    const tse_real w2 = s_a * s_a + s_b * s_b + TSE_R(2.0) * g->c * s_a * s_b;
    out->w = tse_sqrt(w2);
    const tse_real scale = loc->rho2 + g->p.L * g->p.L + tse_fabs(g->g) * w2 + s_a * s_a + s_b * s_b;
    const int solves = tse_fabs(F[0]) + tse_fabs(F[1]) <= tse_sqrt(TSE_REAL_EPS) * scale;
    return solves && out->det > TSE_R(0.0) && s_a > TSE_R(0.0) && s_b > TSE_R(0.0);
}

static int within_limits(const tse_geometry *g, const tse_scissor_solution *s)
{
    return s->s_a >= g->p.s_min && s->s_a <= g->p.s_max && s->s_b >= g->p.s_min &&
           s->s_b <= g->p.s_max && s->w >= g->w_lo && s->w <= g->w_hi;
}

/* Every solution, from the real roots of the quartic 4 m^2 F2 = 0 in m = (s_A - u) + (s_B - v)
 * (kinematics.md, solver notes); each root is polished by Newton on the original pair.  Keeps the
 * physical one that is inside the limits if any, then the one nearest the seed. */
static int enumerate(const tse_geometry *g, const tse_scissor_local *loc, tse_real seed_a,
                     tse_real seed_b, tse_scissor_solution *best, int *iterations)
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
        newton(g, loc, &a, &b, POLISH_MAX_ITER, iterations);
        tse_scissor_solution cand;
        /* A polish that wandered off a spurious root leaves a residual far above rounding. */
        if (!describe(g, loc, a, b, &cand))
            continue;
        const int in = within_limits(g, &cand);
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

tse_status tse_scissor_solve_local(const tse_geometry *g, const tse_scissor_local *loc,
                                   tse_real seed_a, tse_real seed_b, tse_scissor_solution *out)
{
    out->fallback = 0;
    tse_real a = seed_a, b = seed_b;
    int iterations = 0;
    if (newton(g, loc, &a, &b, NEWTON_MAX_ITER, &iterations) && describe(g, loc, a, b, out) &&
        within_limits(g, out)) {
        out->iterations = iterations;
        return TSE_OK;
    }
    /* Newton stalled, left the sheet, or found a solution outside the limits while another might
     * be inside them: only the full enumeration can tell. */
    tse_scissor_solution best;
    const int found = enumerate(g, loc, seed_a, seed_b, &best, &iterations);
    if (found) {
        *out = best;
    } else {
        /* Leave something printable for diagnostics. */
        describe(g, loc, a, b, out);
    }
    out->iterations = iterations;
    out->fallback = 1;
    return found ? TSE_OK : TSE_UNREACHABLE;
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
