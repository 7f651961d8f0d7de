#include "tse/geometry.h"

#include "kin_internal.h"

#include <stdint.h>
#include <string.h>

/* The next representable value above (up) or below a finite x >= 0: its bits as an integer, plus
 * or minus one (the board's build has no libm to call nextafterf from). */
static tse_real next_real(tse_real x, int up)
{
#if defined(TSE_REAL_FLOAT) && TSE_REAL_FLOAT
    uint32_t bits;
#else
    uint64_t bits;
#endif
    if (!up && x == TSE_R(0.0))
        return x;
    memcpy(&bits, &x, sizeof bits);
    bits = up ? bits + 1u : bits - 1u;
    memcpy(&x, &bits, sizeof bits);
    return x;
}

tse_param_id tse_geometry_init(tse_geometry *g, const tse_params *p)
{
    tse_param_id bad = tse_params_check(p);
    if (bad != TSE_PARAM_OK)
        return bad;

    g->p = *p;
    g->l0 = p->k1 * p->L;
    g->r_act = p->k3 * p->L;
    g->r_top = p->k4 * p->L;
    g->inv_r_top = TSE_R(1.0) / g->r_top;
    const tse_real ratio = TSE_R(1.0) / p->k1;
    g->g = (TSE_R(1.0) - ratio * ratio) / TSE_R(4.0);
    g->c = tse_cos(TSE_R(2.0) * p->eta);
    /* w = 2 l0 cos(alpha) falls as alpha rises: the stops become a band on w, no acos needed. */
    g->w_hi = TSE_R(2.0) * g->l0 * tse_cos(p->alpha_min);
    g->w_lo = TSE_R(2.0) * g->l0 * tse_cos(p->alpha_max);
    /* The rounded square root is monotone, so {x : sqrt(x) >= w_lo} is [w_lo2, inf) for one
     * w_lo2 within an ulp or two of w_lo^2: found by stepping from the rounded square. */
    tse_real lo2 = g->w_lo * g->w_lo, hi2 = g->w_hi * g->w_hi;
    while (tse_sqrt(lo2) < g->w_lo)
        lo2 = next_real(lo2, 1);
    while (lo2 > TSE_R(0.0) && tse_sqrt(next_real(lo2, 0)) >= g->w_lo)
        lo2 = next_real(lo2, 0);
    while (hi2 > TSE_R(0.0) && tse_sqrt(hi2) > g->w_hi)
        hi2 = next_real(hi2, 0);
    while (tse_sqrt(next_real(hi2, 1)) <= g->w_hi)
        hi2 = next_real(hi2, 1);
    g->w_lo2 = lo2;
    g->w_hi2 = hi2;
    /* Bounded Newton steps keep a cold start from jumping sheets (kinematics.md, solver notes). */
    g->step_max = TSE_R(0.1) * p->L;
    /* A solution has |CA| = |CB| >= w / 2, so F2 gives w <= 2 l0 and |CA| <= L; and
     * w^2 - (1 + c)/2 (s_A + s_B)^2 = (1 - c)/2 (s_A - s_B)^2 >= 0, so positive slides are each at
     * most 2 l0 sqrt(2 / (1 + c)).  A ball joint farther than L plus that from O has no physical
     * solution: said at once, before the equations' terms could overflow into a false root. */
    const tse_real reach = (p->L + TSE_R(2.0) * g->l0 * tse_sqrt(TSE_R(2.0) / (TSE_R(1.0) + g->c))) *
                           (TSE_R(1.0) + TSE_R(16.0) * TSE_REAL_EPS);
    g->reach2 = reach * reach;
    /* The slides carry the rounding of F's terms, of the size of (L + r_act + r_top)^2, through M's
     * inverse; scissor_core.h says how that bounds mu's error. */
    const tse_real span = p->L + g->r_act + g->r_top;
    g->mu_guard = TSE_REAL_EPS * span * span;
    tse_newton_limits(g);

    /* Exact values at 0, 120 and 240 degrees keep the three scissors bit-for-bit symmetric. */
    const tse_real half_sqrt3 = TSE_R(0.86602540378443864676);
    const tse_real cb[3] = {TSE_R(1.0), TSE_R(-0.5), TSE_R(-0.5)};
    const tse_real sb[3] = {TSE_R(0.0), half_sqrt3, -half_sqrt3};
    const tse_real ce = tse_cos(p->eta), se = tse_sin(p->eta);
    for (int i = 0; i < 3; ++i) {
        tse_scissor_frame *f = &g->sc[i];
        const tse_real er[2] = {cb[i], sb[i]};
        const tse_real et[2] = {-sb[i], cb[i]};
        for (int k = 0; k < 2; ++k) {
            f->er[k] = er[k];
            f->o[k] = g->r_act * er[k];
            f->a[k] = ce * et[k] + se * er[k];
            f->b[k] = -ce * et[k] + se * er[k];
        }
    }

    const tse_real z_home = p->L * tse_sin(TSE_R(0.5) * (p->alpha_min + p->alpha_max));
    for (int k = 0; k < 6; ++k)
        g->home_pose[k] = TSE_R(0.0);
    g->home_pose[TSE_Z] = z_home;
    g->home_s = tse_vertical_slide(g, z_home);
    /* A design without a symmetric solution at mid height still needs some seed; the quartic
     * fallback of the solver does not depend on it. */
    if (!isfinite(g->home_s))
        g->home_s = TSE_R(0.5) * g->l0;
    return TSE_PARAM_OK;
}

/* On the vertical axis u = v = u0 and s_A = s_B = s solves F1; F2 becomes
 * A s^2 - 2 u0 s + (rho2 - L^2) = 0 with A = 1 - 2 g (1 + c) >= 1, and det M = 4 (s - u0)(A s - u0). */
tse_real tse_vertical_slide(const tse_geometry *g, tse_real z)
{
    const tse_real d = g->r_top - g->r_act;
    const tse_real u0 = d * tse_sin(g->p.eta);
    const tse_real A = TSE_R(1.0) - TSE_R(2.0) * g->g * (TSE_R(1.0) + g->c);
    const tse_real k = d * d + z * z - g->p.L * g->p.L;
    const tse_real disc = u0 * u0 - A * k;
    if (!(disc >= TSE_R(0.0)))
        return (tse_real)NAN;
    const tse_real root = tse_sqrt(disc);
    /* Larger root first: it is the home branch of any practical design. */
    const tse_real cand[2] = {(u0 + root) / A, (u0 - root) / A};
    for (int j = 0; j < 2; ++j) {
        const tse_real s = cand[j];
        if (s > TSE_R(0.0) && (s - u0) * (A * s - u0) > TSE_R(0.0))
            return s;
    }
    return (tse_real)NAN;
}
