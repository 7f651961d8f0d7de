/* The per-scissor solver's hot part, inline: the inverse kinematics runs it three times a pose,
 * and a call per scissor (with its saved registers and the solution passed through memory) cost
 * more than the arithmetic of a warm solve.  scissor.c holds the rest (the quartic fallback). */
#ifndef TSE_SCISSOR_CORE_H
#define TSE_SCISSOR_CORE_H

#include "kin_internal.h"

/* The constants of one ball joint that every evaluation needs. */
typedef struct {
    tse_real u, v;     /* d . a_i, d . b_i */
    tse_real k;        /* rho2 - L^2 */
    tse_real g, c;
    tse_real c2;       /* 2 c */
} scissor_consts;

/* Everything one evaluation at (s_a, s_b) gives: F1 and F2 in the spec's polynomial form, whose
 * terms are of the size of the slides times the ball joint's offsets (s_a (s_a - 2u), formed from
 * ea as s_a ((s_a - u) - u); a rearrangement around ea^2 would round on the scale of u^2, several
 * times more in float), and
 * M / 2 = [ea, -eb; m21, m22] with ea = s_a - u, eb = s_b - v, whose determinant is det M / 4.
 * Halving M keeps the Newton step's arithmetic exact in the factor (the 2 moves into one
 * constant). */
typedef struct {
    tse_real ea, eb;   /* s_a - u, s_b - v: M's first row, halved */
    tse_real m21, m22; /* M's second row, halved */
    tse_real F1, F2;
    tse_real det;      /* det M / 4 */
    tse_real w2;       /* base width squared */
} scissor_point;

static inline void scissor_localize_inline(const tse_scissor_frame *f, const tse_real C[3],
                                           tse_scissor_local *loc)
{
    loc->d[0] = C[0] - f->o[0];
    loc->d[1] = C[1] - f->o[1];
    loc->d[2] = C[2];
    loc->u = loc->d[0] * f->a[0] + loc->d[1] * f->a[1];
    loc->v = loc->d[0] * f->b[0] + loc->d[1] * f->b[1];
    loc->rho2 = loc->d[0] * loc->d[0] + loc->d[1] * loc->d[1] + loc->d[2] * loc->d[2];
}

static inline void scissor_consts_of(const tse_geometry *g, const tse_scissor_local *loc, scissor_consts *k)
{
    k->u = loc->u;
    k->v = loc->v;
    k->k = loc->rho2 - g->L2;
    k->g = g->g;
    k->c = g->c;
    k->c2 = TSE_R(2.0) * g->c;
}

static inline void scissor_eval_point(const scissor_consts *k, tse_real s_a, tse_real s_b, scissor_point *pt)
{
    const tse_real ea = s_a - k->u, eb = s_b - k->v;
    /* p and r are the halves of d(w2)/d(s_a) and d(w2)/d(s_b); w2 = s_a p + s_b r. */
    const tse_real p = s_a + k->c * s_b, r = s_b + k->c * s_a;
    const tse_real pa = s_a * (ea - k->u);
    pt->ea = ea;
    pt->eb = eb;
    pt->w2 = s_a * p + s_b * r;
    pt->F1 = pa - s_b * (eb - k->v);
    pt->F2 = (pa + k->k) - k->g * pt->w2;
    pt->m21 = ea - k->g * p;
    pt->m22 = -(k->g * r);
    pt->det = ea * pt->m22 + eb * pt->m21;
}

/* Stroke and the alpha stops (as the band w_lo <= w <= w_hi). */
static inline int scissor_in_limits(const tse_geometry *g, tse_real s_a, tse_real s_b, tse_real w)
{
    return s_a >= g->p.s_min && s_a <= g->p.s_max && s_b >= g->p.s_min && s_b <= g->p.s_max &&
           w >= g->w_lo && w <= g->w_hi;
}

static inline int scissor_within_limits(const tse_geometry *g, const tse_scissor_solution *s)
{
    return scissor_in_limits(g, s->s_a, s->s_b, s->w);
}

/* Fills everything but the iteration counts from the evaluation pt at (s_a, s_b), and returns 1
 * when the point solves the pair and lies on the physical sheet (det M > 0, positive slides),
 * and with limits also inside the stroke and the stops.
 *
 * Solves: a stalled iteration leaves |F| of 1e-2 and more, a root at most the stopping error
 * times |M| plus rounding; sqrt(eps) of the size of F's terms lies well between (9e-8 in double,
 * 2e-3 in float). */
static inline int scissor_describe(const tse_geometry *g, const scissor_consts *k, tse_real rho2,
                                   tse_real s_a, tse_real s_b, const scissor_point *pt, int limits,
                                   tse_scissor_solution *out)
{
    out->s_a = s_a;
    out->s_b = s_b;
    out->det = TSE_R(4.0) * pt->det;
    /* mu = det M / (|row 1| |row 2|), every factor of 2 cancelling. */
    const tse_real n1 = pt->ea * pt->ea + pt->eb * pt->eb;
    const tse_real n2 = pt->m21 * pt->m21 + pt->m22 * pt->m22;
    out->mu = pt->det / tse_sqrt(n1 * n2);
    const tse_real w = tse_sqrt(pt->w2);
    out->w = w;
    const tse_real scale = rho2 + g->L2 + tse_fabs(k->g) * pt->w2 + s_a * s_a + s_b * s_b;
    const int solves = tse_fabs(pt->F1) + tse_fabs(pt->F2) <= tse_sqrt(TSE_REAL_EPS) * scale;
    return solves && pt->det > TSE_R(0.0) && s_a > TSE_R(0.0) && s_b > TSE_R(0.0) &&
           (!limits || scissor_in_limits(g, s_a, s_b, w));
}

/* scissor_describe for the point the steps of scissor_newton's quadratic regime end on, without
 * the residual check: F there is, exactly but for the rounding of the first step's 2x2 solve,
 * the quadratic part of the last step, Q(n_2) (or dM(n_2) n_3 + Q(n_3) after the chord step): of
 * order acc^2 / L, orders below the check's sqrt(eps) of the terms.  So only M, w and the sheet
 * are evaluated, and the F of an evaluation is not (it is most of what one costs). */
static inline int scissor_describe_settled(const tse_geometry *g, const scissor_consts *k, tse_real s_a,
                                           tse_real s_b, int limits, tse_scissor_solution *out)
{
    const tse_real ea = s_a - k->u, eb = s_b - k->v;
    const tse_real p = s_a + k->c * s_b, r = s_b + k->c * s_a;
    const tse_real m21 = ea - k->g * p, m22 = -(k->g * r);
    const tse_real det = ea * m22 + eb * m21;
    const tse_real w2 = s_a * p + s_b * r;
    out->s_a = s_a;
    out->s_b = s_b;
    out->det = TSE_R(4.0) * det;
    out->mu = det / tse_sqrt((ea * ea + eb * eb) * (m21 * m21 + m22 * m22));
    const tse_real w = tse_sqrt(w2);
    out->w = w;
    return det > TSE_R(0.0) && s_a > TSE_R(0.0) && s_b > TSE_R(0.0) &&
           (!limits || scissor_in_limits(g, s_a, s_b, w));
}

/* scissor_describe at a point not evaluated yet. */
static inline int scissor_describe_at(const tse_geometry *g, const scissor_consts *k, tse_real rho2,
                                      tse_real s_a, tse_real s_b, tse_scissor_solution *out)
{
    scissor_point pt;
    scissor_eval_point(k, s_a, s_b, &pt);
    return scissor_describe(g, k, rho2, s_a, s_b, &pt, 0, out);
}

/* Newton from (s_a, s_b) with steps bounded by step_max, then scissor_describe on the point it
 * ends on, from the evaluation it has in hand there.
 *
 * F is quadratic in the slides: from a point x with residual F and Jacobian M, F at x - D is
 * exactly F - M D + Q(D), Q being F's quadratic part, and M at x - D is M - dM(D), linear in D.
 * So after a Newton step dx the residual at x - dx is Q(dx) (F - M dx vanishes by the step's
 * construction), and the next Newton step, M(x - dx)^-1 Q(dx), needs no evaluation of F: in
 * Newton's quadratic regime (dx below 1e-3 L) each evaluation is followed by two steps.
 * Outside that regime (a far seed) the second correction is a chord step M^-1 Q(dx) with the
 * same factorisation (Traub's method), which still saves steps; a clipped step takes none.
 *
 * Ends:
 * - on a point whose own Newton step is below acc = 1e-4 sqrt(eps) L (2.6e-12 m in double,
 *   6e-8 m in float): its error is that step, to first order, and the step is not taken;
 * - on the point after two steps n_1, n_2 that show (at least) quadratic convergence
 *   (n_2 <= n_1 / 4) and predict an error n_2^3 / n_1^2 below acc (or after a third, chord,
 *   step when they do not, as below): a warm seed a millimetre off then takes one evaluation,
 *   the two steps, and M and w where they end (scissor_describe_settled).
 * A small step is not proof of a root in general (it can stall where |F| has a minimum), hence
 * the residual check of scissor_describe wherever the iteration ends on an evaluation; after the
 * steps from one evaluation the residual is known (scissor_describe_settled).  With limits, the
 * verdict includes the stroke and the stops.  Returns -1 when Newton gives up (out and
 * (s_a, s_b) untouched), else the verdict on the point, left in (s_a, s_b). */
static inline int scissor_newton(const tse_geometry *g, const scissor_consts *k, tse_real rho2, tse_real *s_a,
                                 tse_real *s_b, int max_iter, int limits, int *iterations, tse_scissor_solution *out)
{
    tse_real a = *s_a, b = *s_b;
    scissor_point pt;
    for (int it = 0;; ++it) {
        scissor_eval_point(k, a, b, &pt);
        /* M dx = F with M = 2 [ea, -eb; m21, m22]: the 1/2 rides on the inverse determinant.
         * A zero or non-finite determinant or residual makes the step non-finite: caught below. */
        const tse_real inv = TSE_R(0.5) / pt.det;
        tse_real da = (pt.m22 * pt.F1 + pt.eb * pt.F2) * inv;
        tse_real db = (pt.ea * pt.F2 - pt.m21 * pt.F1) * inv;
        const tse_real n2 = da * da + db * db;
        if (n2 <= g->newton_acc2)
            break;
        if (it == max_iter)
            return -1;
        /* Q(dx) = (da^2 - db^2, da^2 - g (da^2 + db^2 + 2 c da db)): the residual at x - dx. */
        const tse_real aa = da * da, bb = db * db;
        const tse_real q1 = aa - bb;
        const tse_real q2 = aa - k->g * ((aa + bb) + k->c2 * (da * db));
        if (n2 <= g->newton_regime2) {
            /* M / 2 at x - dx: ea and eb fall by the step, and the second row by
             * (da, -db) - g (da + c db, db + c da). */
            const tse_real ea = pt.ea - da, eb = pt.eb - db;
            const tse_real m21 = pt.m21 - (da - k->g * (da + k->c * db));
            const tse_real m22 = pt.m22 + k->g * (db + k->c * da);
            const tse_real inv2 = TSE_R(0.5) / (ea * m22 + eb * m21);
            const tse_real ea2 = (m22 * q1 + eb * q2) * inv2;
            const tse_real eb2 = (ea * q2 - m21 * q1) * inv2;
            const tse_real e2 = ea2 * ea2 + eb2 * eb2;
            a -= da + ea2;
            b -= db + eb2;
            *iterations += 2;
            if (TSE_R(16.0) * e2 <= n2) {
                /* n_2 <= n_1 / 4 and n_2^3 <= acc n_1^2, squared. */
                if (e2 * e2 * e2 <= g->newton_acc2 * n2 * n2) {
                    *s_a = a;
                    *s_b = b;
                    return scissor_describe_settled(g, k, a, b, limits, out);
                }
                /* Short of that, the residual Q(n_2) left by the second step, with the second
                 * step's factorisation: the error left is then about K n_2 n_3, K about
                 * n_2 / n_1^2. */
                const tse_real a2 = ea2 * ea2, b2 = eb2 * eb2;
                const tse_real r1 = a2 - b2;
                const tse_real r2 = a2 - k->g * ((a2 + b2) + k->c2 * (ea2 * eb2));
                const tse_real ea3 = (m22 * r1 + eb * r2) * inv2;
                const tse_real eb3 = (ea * r2 - m21 * r1) * inv2;
                const tse_real e3 = ea3 * ea3 + eb3 * eb3;
                a -= ea3;
                b -= eb3;
                *iterations += 1;
                if (TSE_R(16.0) * e3 <= e2 && e2 * e2 * e3 <= g->newton_acc2 * n2 * n2) {
                    *s_a = a;
                    *s_b = b;
                    return scissor_describe_settled(g, k, a, b, limits, out);
                }
            }
            continue;
        }
        if (n2 <= g->newton_max2) {
            da += (pt.m22 * q1 + pt.eb * q2) * inv;
            db += (pt.ea * q2 - pt.m21 * q1) * inv;
        } else {
            if (!(n2 < (tse_real)INFINITY))
                return -1;
            const tse_real t = g->step_max / tse_sqrt(n2);
            da *= t;
            db *= t;
        }
        a -= da;
        b -= db;
        *iterations += 1;
    }
    *s_a = a;
    *s_b = b;
    return scissor_describe(g, k, rho2, a, b, &pt, limits, out);
}

/* tse_scissor_solve_local's common case: Newton from the seed lands on a physical solution
 * inside the limits; returns 1 with out filled.  Otherwise 0, with where Newton got to (the seed
 * if it failed) and its iterations, for tse_scissor_fallback (scissor.c). */
static inline int scissor_solve_fast(const tse_geometry *g, const tse_scissor_local *loc, tse_real *s_a,
                                     tse_real *s_b, int *iterations, tse_scissor_solution *out)
{
    scissor_consts k;
    scissor_consts_of(g, loc, &k);
    *iterations = 0;
    if (!(loc->rho2 <= g->reach2))
        return 0; /* no physical solution at all: tse_scissor_fallback says so */
    if (scissor_newton(g, &k, loc->rho2, s_a, s_b, TSE_NEWTON_MAX_ITER, 1, iterations, out) == 1) {
        out->iterations = *iterations;
        out->fallback = 0;
        return 1;
    }
    return 0;
}

#endif
