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

/* What a solve's verdict covers, and what it may leave out. */
enum {
    SCISSOR_LIMITS = 1,     /* the verdict includes the stroke and the stops */
    SCISSOR_SKIP_WIDTH = 2, /* out->w may be left unset (a square root the caller has no use for) */
};

static inline int scissor_in_stroke(const tse_geometry *g, tse_real s_a, tse_real s_b)
{
    return s_a >= g->p.s_min && s_a <= g->p.s_max && s_b >= g->p.s_min && s_b <= g->p.s_max;
}

/* Stroke and the alpha stops, as the band w_lo2 <= w^2 <= w_hi2 (geometry.h: the same verdict as
 * w = sqrt(w^2) against w_lo, w_hi, as scissor_within_limits takes it). */
static inline int scissor_in_limits(const tse_geometry *g, tse_real s_a, tse_real s_b, tse_real w2)
{
    return scissor_in_stroke(g, s_a, s_b) && w2 >= g->w_lo2 && w2 <= g->w_hi2;
}

static inline int scissor_within_limits(const tse_geometry *g, const tse_scissor_solution *s)
{
    return scissor_in_stroke(g, s->s_a, s->s_b) && s->w >= g->w_lo && s->w <= g->w_hi;
}

/* The type-1 check of kinematics.md on a solution, with room for its slides' error.
 *
 * The solver's slides miss the exact ones by the rounding of F, whose terms are of the size of
 * span^2 = (L + r_act + r_top)^2 (the ball joint's rounding enters through rho2, u and v alike),
 * carried through M's inverse: |dq| <~ eps span^2 / sigma_min(M / 2).  mu is the sine of the angle
 * between M's rows, and a row turns by at most its change over its length, so mu moves by about
 * |dq| / sqrt(n_min); with sigma_min(M / 2) >= det(M / 2) / sqrt(n1 + n2) and det(M / 2) =
 * mu sqrt(n1 n2), that is a few eps span^2 / (mu n_min).  Near a scissor's bifurcation row 1
 * shrinks (to 6e-4 m where the kin fuzz target found float slides 0.3 mm off and mu 0.18 where the
 * exact one is 0.033), and mu computed there means nothing.  Against a long-double solution over
 * the workspace and around that pose the error stayed within 0.14 eps span^2 / (mu n_min), so
 * mu_guard = eps span^2 gives seven times that: on the prototype's workspace near mu_min it asks
 * 1e-4 to 6e-4 more of a float mu, 1e-12 of a double one.  Solutions lie on the det M > 0 sheet,
 * so mu > 0 (or NaN, which fails), and with mu_guard > 0 the product form is
 * mu - mu_guard / (mu n_min) >= mu_min, which implies mu >= mu_min. */
static inline int scissor_mu_clear(const tse_geometry *g, const tse_scissor_solution *s)
{
    return (s->mu - g->p.mu_min) * (s->mu * s->n_min) >= g->mu_guard;
}

/* mu and n_min from det(M / 2) and M / 2's rows (ea, -eb) and (m21, m22): every factor of 2
 * cancels in mu. */
static inline void scissor_margin(tse_real det, tse_real ea, tse_real eb, tse_real m21, tse_real m22,
                                  tse_scissor_solution *out)
{
    const tse_real n1 = ea * ea + eb * eb, n2 = m21 * m21 + m22 * m22;
    out->mu = det / tse_sqrt(n1 * n2);
    out->n_min = n1 < n2 ? n1 : n2;
}

/* Fills everything but the iteration counts from the evaluation pt at (s_a, s_b), and returns 1
 * when the point solves the pair and lies on the physical sheet (det M > 0, positive slides),
 * and with SCISSOR_LIMITS in flags also inside the stroke and the stops.
 *
 * Solves: a stalled iteration leaves |F| of 1e-2 and more, a root at most the stopping error
 * times |M| plus rounding; sqrt(eps) of the size of F's terms lies well between (9e-8 in double,
 * 2e-3 in float). */
static inline int scissor_describe(const tse_geometry *g, const scissor_consts *k, tse_real rho2,
                                   tse_real s_a, tse_real s_b, const scissor_point *pt, int flags,
                                   tse_scissor_solution *out)
{
    out->s_a = s_a;
    out->s_b = s_b;
    out->det = TSE_R(4.0) * pt->det;
    scissor_margin(pt->det, pt->ea, pt->eb, pt->m21, pt->m22, out);
    const tse_real w = tse_sqrt(pt->w2);
    out->w = w;
    const tse_real scale = rho2 + g->L2 + tse_fabs(k->g) * pt->w2 + s_a * s_a + s_b * s_b;
    const int solves = tse_fabs(pt->F1) + tse_fabs(pt->F2) <= tse_sqrt(TSE_REAL_EPS) * scale;
    return solves && pt->det > TSE_R(0.0) && s_a > TSE_R(0.0) && s_b > TSE_R(0.0) &&
           (!(flags & SCISSOR_LIMITS) || scissor_in_limits(g, s_a, s_b, pt->w2));
}

/* scissor_describe for the point the steps of scissor_newton's quadratic regime end on, without
 * the residual check: F there is, exactly but for the rounding of the first step's 2x2 solve,
 * the quadratic part of the last step, Q(n_2) (or dM(n_2) n_3 + Q(n_3) after the chord step): of
 * order acc^2 / L, orders below the check's sqrt(eps) of the terms.  So only M, w and the sheet
 * are evaluated, and the F of an evaluation is not (it is most of what one costs).  The stops are
 * checked on w^2, so w's square root is taken only for a caller that wants w. */
static inline int scissor_describe_settled(const tse_geometry *g, const scissor_consts *k, tse_real s_a,
                                           tse_real s_b, int flags, tse_scissor_solution *out)
{
    const tse_real ea = s_a - k->u, eb = s_b - k->v;
    const tse_real p = s_a + k->c * s_b, r = s_b + k->c * s_a;
    const tse_real m21 = ea - k->g * p, m22 = -(k->g * r);
    const tse_real det = ea * m22 + eb * m21;
    const tse_real w2 = s_a * p + s_b * r;
    out->s_a = s_a;
    out->s_b = s_b;
    out->det = TSE_R(4.0) * det;
    scissor_margin(det, ea, eb, m21, m22, out);
    if (!(flags & SCISSOR_SKIP_WIDTH))
        out->w = tse_sqrt(w2);
    return det > TSE_R(0.0) && s_a > TSE_R(0.0) && s_b > TSE_R(0.0) &&
           (!(flags & SCISSOR_LIMITS) || scissor_in_limits(g, s_a, s_b, w2));
}

/* scissor_describe at a point not evaluated yet. */
static inline int scissor_describe_at(const tse_geometry *g, const scissor_consts *k, tse_real rho2,
                                      tse_real s_a, tse_real s_b, int flags, tse_scissor_solution *out)
{
    scissor_point pt;
    scissor_eval_point(k, s_a, s_b, &pt);
    return scissor_describe(g, k, rho2, s_a, s_b, &pt, flags, out);
}

/* One Newton step from the evaluation pt: M dx = F with M = 2 [ea, -eb; m21, m22], the 1/2 riding
 * on the inverse determinant.  A zero or non-finite determinant or residual makes the step
 * non-finite (scissor_newton stops on it). */
typedef struct {
    tse_real inv;    /* 1 / (2 det(M / 2)) */
    tse_real da, db; /* the step, to be subtracted */
    tse_real n2;     /* its squared length */
    tse_real q1, q2; /* Q(dx) = (da^2 - db^2, da^2 - g (da^2 + db^2 + 2 c da db)): F at x - dx */
} scissor_step;

/* The step, without Q (scissor_step_quad): a Newton that stops at this step has no use for it. */
static inline void scissor_step_of(const scissor_point *pt, scissor_step *s)
{
    s->inv = TSE_R(0.5) / pt->det;
    s->da = (pt->m22 * pt->F1 + pt->eb * pt->F2) * s->inv;
    s->db = (pt->ea * pt->F2 - pt->m21 * pt->F1) * s->inv;
    s->n2 = s->da * s->da + s->db * s->db;
}

static inline void scissor_step_quad(const scissor_consts *k, scissor_step *s)
{
    const tse_real aa = s->da * s->da, bb = s->db * s->db;
    s->q1 = aa - bb;
    s->q2 = aa - k->g * ((aa + bb) + k->c2 * (s->da * s->db));
}

/* The second step of the quadratic regime, from M at x - dx and the residual Q(dx) there. */
typedef struct {
    tse_real ea, eb, m21, m22; /* M / 2 at x - dx */
    tse_real inv2;             /* 1 / (2 det(M / 2)) there */
    tse_real ea2, eb2;         /* the step */
    tse_real e2;               /* its squared length */
} scissor_second;

static inline void scissor_second_of(const scissor_consts *k, const scissor_point *pt, const scissor_step *s,
                                     scissor_second *t)
{
    /* ea and eb fall by the step, and the second row by (da, -db) - g (da + c db, db + c da). */
    t->ea = pt->ea - s->da;
    t->eb = pt->eb - s->db;
    t->m21 = pt->m21 - (s->da - k->g * (s->da + k->c * s->db));
    t->m22 = pt->m22 + k->g * (s->db + k->c * s->da);
    t->inv2 = TSE_R(0.5) / (t->ea * t->m22 + t->eb * t->m21);
    t->ea2 = (t->m22 * s->q1 + t->eb * s->q2) * t->inv2;
    t->eb2 = (t->ea * s->q2 - t->m21 * s->q1) * t->inv2;
    t->e2 = t->ea2 * t->ea2 + t->eb2 * t->eb2;
}

/* Whether two steps of squared lengths n2, e2 show quadratic convergence (n_2 <= n_1 / 4) and
 * predict an error n_2^3 / n_1^2 below acc, squared. */
static inline int scissor_settles(const tse_geometry *g, tse_real n2, tse_real e2)
{
    return TSE_R(16.0) * e2 <= n2 && e2 * e2 * e2 <= g->newton_acc2 * n2 * n2;
}

/* Where one scissor's Newton is: scissor_newton_pass advances it by one evaluation. */
typedef struct {
    tse_real a, b;  /* the slides reached */
    int it;         /* passes made */
    int iterations; /* Newton steps taken (one to three a pass) */
} scissor_run;

/* scissor_newton_pass's answer while the iteration goes on (besides -1, 0 and 1). */
enum { SCISSOR_GOING = 2 };

/* One evaluation of scissor_newton and the steps after it: SCISSOR_GOING with r advanced, or
 * scissor_newton's answer.  Scissors are independent, so a caller may advance several in turn
 * (tse_ik), each ending as scissor_newton would alone. */
static TSE_ALWAYS_INLINE int scissor_newton_pass(const tse_geometry *g, const scissor_consts *k, tse_real rho2,
                                                 int max_iter, int flags, scissor_run *r,
                                                 tse_scissor_solution *out)
{
    scissor_point pt;
    scissor_eval_point(k, r->a, r->b, &pt);
    scissor_step s;
    scissor_step_of(&pt, &s);
    if (s.n2 <= g->newton_acc2)
        return scissor_describe(g, k, rho2, r->a, r->b, &pt, flags, out);
    if (r->it == max_iter)
        return -1;
    r->it++;
    scissor_step_quad(k, &s);
    if (s.n2 <= g->newton_regime2) {
        scissor_second t;
        scissor_second_of(k, &pt, &s, &t);
        r->a -= s.da + t.ea2;
        r->b -= s.db + t.eb2;
        r->iterations += 2;
        if (TSE_R(16.0) * t.e2 <= s.n2) {
            if (scissor_settles(g, s.n2, t.e2))
                return scissor_describe_settled(g, k, r->a, r->b, flags, out);
            /* Short of that, the residual Q(n_2) left by the second step, with the second step's
             * factorisation: the error left is then about K n_2 n_3, K about n_2 / n_1^2. */
            const tse_real a2 = t.ea2 * t.ea2, b2 = t.eb2 * t.eb2;
            const tse_real r1 = a2 - b2;
            const tse_real r2 = a2 - k->g * ((a2 + b2) + k->c2 * (t.ea2 * t.eb2));
            const tse_real ea3 = (t.m22 * r1 + t.eb * r2) * t.inv2;
            const tse_real eb3 = (t.ea * r2 - t.m21 * r1) * t.inv2;
            const tse_real e3 = ea3 * ea3 + eb3 * eb3;
            r->a -= ea3;
            r->b -= eb3;
            r->iterations += 1;
            if (TSE_R(16.0) * e3 <= t.e2 && t.e2 * t.e2 * e3 <= g->newton_acc2 * s.n2 * s.n2)
                return scissor_describe_settled(g, k, r->a, r->b, flags, out);
        }
        return SCISSOR_GOING;
    }
    tse_real da = s.da, db = s.db;
    if (s.n2 <= g->newton_max2) {
        da += (pt.m22 * s.q1 + pt.eb * s.q2) * s.inv;
        db += (pt.ea * s.q2 - pt.m21 * s.q1) * s.inv;
    } else {
        if (!(s.n2 < (tse_real)INFINITY))
            return -1;
        const tse_real t = g->step_max / tse_sqrt(s.n2);
        da *= t;
        db *= t;
    }
    r->a -= da;
    r->b -= db;
    r->iterations += 1;
    return SCISSOR_GOING;
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
 * steps from one evaluation the residual is known (scissor_describe_settled).  flags as
 * scissor_describe's and scissor_describe_settled's.  Returns -1 when Newton gives up (out and
 * (s_a, s_b) untouched), else the verdict on the point, left in (s_a, s_b).  It is a loop of
 * scissor_newton_pass; scissor_warm_steps and scissor_warm_end are its first pass, split. */
static TSE_ALWAYS_INLINE int scissor_newton(const tse_geometry *g, const scissor_consts *k, tse_real rho2, tse_real *s_a,
                                            tse_real *s_b, int max_iter, int flags, int *iterations,
                                            tse_scissor_solution *out)
{
    scissor_run r = {*s_a, *s_b, 0, 0};
    int v;
    do
        v = scissor_newton_pass(g, k, rho2, max_iter, flags, &r, out);
    while (v == SCISSOR_GOING);
    *iterations += r.iterations;
    if (v >= 0) {
        *s_a = r.a;
        *s_b = r.b;
    }
    return v;
}

/* scissor_newton's first pass from a seed, split in two so that a caller can run it for several
 * scissors side by side: scissor_warm_steps is its arithmetic, without a branch (an out-of-order
 * core then overlaps the scissors' chains of dependent multiplications and divisions, which one
 * after the other is what a warm solve waits on), scissor_warm_end its decision.  Only what the
 * decision needs is kept between the two. */
typedef struct {
    tse_real n2, e2;   /* the two steps' squared lengths */
    tse_real s_a, s_b; /* where they end */
} scissor_warm;

static inline void scissor_warm_steps(const tse_geometry *g, const tse_scissor_local *loc, tse_real s_a,
                                      tse_real s_b, scissor_warm *w)
{
    scissor_consts k;
    scissor_point pt;
    scissor_step s;
    scissor_second t;
    scissor_consts_of(g, loc, &k);
    scissor_eval_point(&k, s_a, s_b, &pt);
    scissor_step_of(&pt, &s);
    scissor_step_quad(&k, &s);
    scissor_second_of(&k, &pt, &s, &t);
    w->n2 = s.n2;
    w->e2 = t.e2;
    w->s_a = s_a - (s.da + t.ea2);
    w->s_b = s_b - (s.db + t.eb2);
}

/* scissor_solve_fast's result when scissor_newton ends on its first pass from (s_a, s_b) with a
 * solution inside the limits (the seed was already one, or the two steps settle): returns 1 with
 * out and *iterations as scissor_solve_fast gives them, the same bit for bit (the same
 * arithmetic in the same order).  Returns 0 in every other case, for scissor_solve_fast to
 * decide from the seed. */
static inline int scissor_warm_end(const tse_geometry *g, const tse_scissor_local *loc, tse_real s_a,
                                   tse_real s_b, const scissor_warm *w, int flags, int *iterations,
                                   tse_scissor_solution *out)
{
    int ok;
    if (!(loc->rho2 <= g->reach2))
        return 0;
    scissor_consts k;
    scissor_consts_of(g, loc, &k);
    if (w->n2 <= g->newton_acc2) {
        /* The seed solves already (as when the forward kinematics verifies its answer). */
        *iterations = 0;
        ok = scissor_describe_at(g, &k, loc->rho2, s_a, s_b, flags, out);
    } else if (w->n2 <= g->newton_regime2 && scissor_settles(g, w->n2, w->e2)) {
        *iterations = 2;
        ok = scissor_describe_settled(g, &k, w->s_a, w->s_b, flags, out);
    } else {
        return 0;
    }
    if (ok != 1)
        return 0;
    out->iterations = *iterations;
    out->fallback = 0;
    return 1;
}

/* tse_scissor_solve_local's common case: Newton from the seed lands on a physical solution
 * inside the limits; returns 1 with out filled.  Otherwise 0, with where Newton got to (the seed
 * if it failed) and its iterations, for tse_scissor_fallback (scissor.c).  With skip_width, out->w
 * may be left unset. */
static TSE_ALWAYS_INLINE int scissor_solve_fast(const tse_geometry *g, const tse_scissor_local *loc, tse_real *s_a,
                                     tse_real *s_b, int skip_width, int *iterations, tse_scissor_solution *out)
{
    scissor_consts k;
    scissor_consts_of(g, loc, &k);
    *iterations = 0;
    if (!(loc->rho2 <= g->reach2))
        return 0; /* no physical solution at all: tse_scissor_fallback says so */
    const int flags = SCISSOR_LIMITS | (skip_width ? SCISSOR_SKIP_WIDTH : 0);
    if (scissor_newton(g, &k, loc->rho2, s_a, s_b, TSE_NEWTON_MAX_ITER, flags, iterations, out) == 1) {
        out->iterations = *iterations;
        out->fallback = 0;
        return 1;
    }
    return 0;
}

#endif
