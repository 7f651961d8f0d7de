#include "fx_scissor.h"

#include "fx_math.h"

#define NEWTON_MAX_ITER 40
#define POLISH_MAX_ITER 12
/* Newton's last step: F is exact in these formats but for one unit of g w^2 (the products of
 * Q24 values are exact in Q48), so at a root the step is the distance to it rounded: one or two
 * units.  A step of at most ACC2 (squared units, Q48) is taken and ends the iteration. */
#define ACC2 8

void fx_localize(const tse_fx_geometry *g, int i, const int64_t C[3], fx_local *loc)
{
    /* The slides are sensitive to F's constants (near a scissor's bifurcation, a hundred times
     * over): d is taken in Q28 (3.7e-9 m) from the Q28 ball joint, rho2 from it in Q50, u and v
     * in Q26 for F (and Q24 for M, whose rounding only slows Newton).  With d, u and v in Q24
     * the slides moved by 1.5 um at a pose of mu 0.24 (tests/kinematics/test_ik_fixed.c).
     * Below 8 m on each axis d is an int32, and every product a 32 x 32 one. */
    const tse_fx_scissor_frame *f = &g->sc[i];
    const int64_t dd[3] = {C[0] - f->o[0], C[1] - f->o[1], C[2]};
    /* 8 m per axis is the largest reach the format takes (ik_fixed.h): beyond, far. */
    const int64_t room = (int64_t)1 << 31;
    loc->far = 1;
    loc->u = loc->v = 0;
    loc->rho2 = 0;
    int32_t d[3];
    for (int k = 0; k < 3; ++k) {
        if (dd[k] >= room || dd[k] <= -room)
            return;
        d[k] = (int32_t)dd[k];
        loc->d[k] = (int32_t)fx_shr(dd[k] + 8, 4);
    }
    const int64_t u58 = (int64_t)d[0] * f->a[0] + (int64_t)d[1] * f->a[1];
    const int64_t v58 = (int64_t)d[0] * f->b[0] + (int64_t)d[1] * f->b[1];
    loc->u = (int32_t)((u58 + ((int64_t)1 << 33)) >> 34);
    loc->v = (int32_t)((v58 + ((int64_t)1 << 33)) >> 34);
    loc->u26 = (int32_t)((u58 + ((int64_t)1 << 31)) >> 32);
    loc->v26 = (int32_t)((v58 + ((int64_t)1 << 31)) >> 32);
    loc->rho2 = (((int64_t)d[0] * d[0] + 32) >> 6) + (((int64_t)d[1] * d[1] + 32) >> 6) + (((int64_t)d[2] * d[2] + 32) >> 6);
    loc->far = (loc->rho2 >> 2) > g->reach2;
}

/* The constants of one ball joint every evaluation needs. */
typedef struct {
    int32_t u, v;     /* Q24 */
    int32_t u26, v26; /* Q26 */
    int64_t k;        /* rho2 - L^2, Q48 (the quartic) */
    int64_t k50;      /* the same in Q50 (F) */
    int32_t g, c;
} consts;

/* One evaluation at (s_a, s_b): F in the polynomial form (exact for its constants but for one
 * unit of g w^2) and M / 2 = [ea, -eb; m21, m22]. */
typedef struct {
    int32_t ea, eb;
    int64_t m21, m22; /* Q24 */
    int64_t F1, F2;   /* Q50 */
    int64_t det;      /* det(M / 2), Q48 */
    int64_t w2;       /* Q48 */
} point;

static void eval_point(const consts *k, int32_t s_a, int32_t s_b, point *pt)
{
    const int32_t ea = s_a - k->u, eb = s_b - k->v;
    /* p and r are the halves of d(w2)/d(s_a) and d(w2)/d(s_b); w2 = s_a p + s_b r. */
    const int32_t p = s_a + (int32_t)fx_shr((int64_t)k->c * s_b, 30);
    const int32_t r = s_b + (int32_t)fx_shr((int64_t)k->c * s_a, 30);
    /* s_a (s_a - 2 u) in Q50, from Q24 x Q26: |s - 2u| <= 24 m, within int32 in Q26. */
    const int64_t pa = (int64_t)s_a * (int32_t)(s_a * 4 - 2 * k->u26);
    pt->ea = ea;
    pt->eb = eb;
    pt->w2 = (int64_t)s_a * p + (int64_t)s_b * r;
    pt->F1 = pa - (int64_t)s_b * (int32_t)(s_b * 4 - 2 * k->v26);
    pt->F2 = pa + k->k50 - fx_mul64x32(pt->w2, k->g, 24);
    pt->m21 = ea - fx_shr((int64_t)k->g * p, 26);
    pt->m22 = -fx_shr((int64_t)k->g * r, 26);
    pt->det = pt->m22 * ea + pt->m21 * eb;
}

/* x^2 + y^2 as m 2^e, whatever the size of x and y (M's second row reaches 2^33 in Q24). */
static fx_scaled norm2sq(int64_t x, int64_t y)
{
    const int bx = fx_bits64(x), by = fx_bits64(y);
    const int k = (bx > by ? bx : by) > 30 ? (bx > by ? bx : by) - 30 : 0;
    const int64_t xs = fx_shr(x, k), ys = fx_shr(y, k);
    return fx_scaled_of(xs * xs + ys * ys, -2 * k);
}

/* A scaled non-negative value as an int64 in its units, saturated. */
static int64_t scaled_to_int(fx_scaled x)
{
    if (x.e > 0 && fx_bits64(x.m) + x.e > 62)
        return INT64_MAX;
    return fx_shl(x.m, x.e);
}

static int in_stroke(const tse_fx_geometry *g, int32_t s_a, int32_t s_b)
{
    return s_a >= g->p.s_min && s_a <= g->p.s_max && s_b >= g->p.s_min && s_b <= g->p.s_max;
}

int fx_within_limits(const tse_fx_geometry *g, const fx_sol *s)
{
    return in_stroke(g, s->s_a, s->s_b) && s->w2 >= g->w_lo2 && s->w2 <= g->w_hi2;
}

int fx_mu_clear(const tse_fx_geometry *g, const fx_sol *s)
{
    /* (mu - mu_min) mu n_min >= mu_guard: the float build's form (scissor_core.h). */
    const int64_t x = fx_shr((int64_t)(s->mu - g->p.mu_min) * s->mu, 30); /* Q30 */
    return fx_mul64x32(s->n_min, (int32_t)x, 30) >= g->mu_guard;
}

/* Fills out from the evaluation pt (at or within a few units of (s_a, s_b)) and returns 1 when
 * the point solves the pair and lies on the physical sheet (and, with limits, inside the stroke
 * and the stops). */
static int describe(const tse_fx_geometry *g, int32_t s_a, int32_t s_b, const point *pt,
                    int limits, fx_sol *out)
{
    out->s_a = s_a;
    out->s_b = s_b;
    out->det = pt->det;
    out->w2 = pt->w2;
    out->ea = pt->ea;
    out->eb = pt->eb;
    /* mu = det / sqrt(n1 n2), n1 and n2 the rows' squared norms: exact in 64 bits while M's
     * second row is below 64 m (every solution's), each brought to at most 32 bits by an even
     * shift for the one square root of their product. */
    const int64_t lim = (int64_t)1 << 30;
    if (pt->m21 < lim && pt->m21 > -lim && pt->m22 < lim && pt->m22 > -lim) {
        const uint64_t n1 = (uint64_t)((int64_t)pt->ea * pt->ea + (int64_t)pt->eb * pt->eb);
        const uint64_t n2 = (uint64_t)(pt->m21 * pt->m21 + pt->m22 * pt->m22);
        const int s1 = n1 >> 32 ? (33 - fx_clz32((uint32_t)(n1 >> 32))) & ~1 : 0;
        const int s2 = n2 >> 32 ? (33 - fx_clz32((uint32_t)(n2 >> 32))) & ~1 : 0;
        const uint64_t root = (uint64_t)fx_isqrt64((n1 >> s1) * (n2 >> s2)) << ((s1 + s2) / 2);
        out->mu = root ? (int32_t)fx_div(pt->det, (int64_t)root, 30) : 0;
        out->n_min = (int64_t)(n1 < n2 ? n1 : n2);
    } else {
        const fx_scaled n1 = norm2sq(pt->ea, pt->eb), n2 = norm2sq(pt->m21, pt->m22);
        const fx_scaled root = fx_scaled_sqrt(fx_scaled_mul(n1, n2));
        out->mu = root.m > 0 ? fx_scaled_div(fx_scaled_of(pt->det, 0), root, 30) : 0;
        const int64_t a1 = scaled_to_int(n1), a2 = scaled_to_int(n2); /* Q48 */
        out->n_min = a1 < a2 ? a1 : a2;
    }
    /* A root leaves |F| = |M dx| with dx the few units Newton stopped short (or its last step);
     * a stall, or the bottom of a near-tangency of the two curves, leaves far more: 16 units
     * through M's entries (Q50: 128 |M / 2|), and a few units for the rounding of g w^2.  (A
     * bound relative to F's terms, 2^-14 or 2^-20 of them, let the fuzz target find both a
     * tangency 5e-6 m^2 from a root and one further off accepted as roots.) */
    const uint64_t m_abs = fx_abs64(pt->ea) + fx_abs64(pt->eb) + fx_abs64(pt->m21) + fx_abs64(pt->m22);
    const int solves = fx_abs64(pt->F1) + fx_abs64(pt->F2) <= 128u * m_abs + 64u;
    return solves && pt->det > 0 && s_a > 0 && s_b > 0 &&
           (!limits || (in_stroke(g, s_a, s_b) && pt->w2 >= g->w_lo2 && pt->w2 <= g->w_hi2));
}

/* (na, nb) 2^sh / den for den's reciprocal rc: fx_mul_recip twice, its shift and rounding
 * worked out once. */
static void step_of(int64_t na, int64_t nb, fx_recip rc, int sh, int64_t *da, int64_t *db)
{
    const int t = 94 - rc.k - sh;
    if (rc.k == 64 || t < 33 || t > 94) {
        *da = fx_mul_recip(na, rc, sh);
        *db = fx_mul_recip(nb, rc, sh);
        return;
    }
    const int32_t r = (int32_t)(rc.r >> 1);
    const int64_t half = (int64_t)1 << (t - 33);
    const int64_t qa = fx_shr(fx_mul64x32(na, r, 31) + half, t - 32);
    const int64_t qb = fx_shr(fx_mul64x32(nb, r, 31) + half, t - 32);
    *da = rc.neg ? -qa : qa;
    *db = rc.neg ? -qb : qb;
}

/* Steps (max norm, units of 2^-24 m) below which the Jacobian's reciprocal is kept from one
 * evaluation to the next (a chord step): its change over such a step is a few thousandths. */
#define CHORD_REGIME ((int64_t)1 << 16)
/* The error an iteration may end with, in units: the next step's predicted size. */
#define SETTLE_ACC 3

/* Bounded Newton from (*s_a, *s_b).  Returns -1 when it gives up (the point left untouched),
 * else describe's verdict on the point it ends on, left in (*s_a, *s_b).
 *
 * A warm seed (a millimetre or so off) is what it is for: one Newton step from the seed's
 * evaluation, then from the next evaluation a chord step with the same reciprocal of det M (the
 * reciprocal is most of a step's cost on a core without a 64-bit divide), and it ends when two
 * steps l1, l2 (max norms) show contraction (l2 <= l1 / 4) and predict the next below SETTLE_ACC
 * (l2^2 / l1): then where it ends is evaluated once more for the checks (M, and F, whose residual
 * tells a contraction towards a minimum of |F| from one towards a root).  A step that does not
 * contract so brings a fresh reciprocal (plain Newton); far from a root steps are clipped to
 * step_max.  A step of at most ACC2 (squared) ends it as well, its evaluation a few units away. */
static int newton(const tse_fx_geometry *g, const consts *k, int32_t *s_a, int32_t *s_b, int max_iter,
                  int limits, int *iterations, fx_sol *out)
{
    int32_t a = *s_a, b = *s_b;
    point pt, jac;          /* this evaluation, and the one whose reciprocal is held */
    fx_recip rc = {0, 64, 0};
    int64_t l_prev = 0;     /* max norm of the previous step; 0 before the first */
    int chord = 0;
    for (int it = 0;; ++it) {
        eval_point(k, a, b, &pt);
        if (!chord) {
            if (pt.det == 0)
                return -1;
            jac = pt;
            rc = fx_recip_of(2 * pt.det);
        }
        /* The step J^-1 F = [m22 F1 + eb F2, ea F2 - m21 F1] / (2 det(J / 2)), with F brought to
         * 26 bits (Q48 or coarser: exact near a root, where it is small) so that the products
         * stay in 64 bits. */
        const int bf = fx_bits64(pt.F1) > fx_bits64(pt.F2) ? fx_bits64(pt.F1) : fx_bits64(pt.F2);
        const int fs = bf > 28 ? bf - 26 : 2;
        const int32_t F1 = (int32_t)fx_shr(pt.F1, fs), F2 = (int32_t)fx_shr(pt.F2, fs);
        int64_t na, nb;
        if (jac.m21 == (int32_t)jac.m21 && jac.m22 == (int32_t)jac.m22) { /* 32 x 32 products */
            na = (int64_t)(int32_t)jac.m22 * F1 + (int64_t)jac.eb * F2;
            nb = (int64_t)jac.ea * F2 - (int64_t)(int32_t)jac.m21 * F1;
        } else {
            na = jac.m22 * F1 + (int64_t)jac.eb * F2;
            nb = (int64_t)jac.ea * F2 - jac.m21 * F1;
        }
        int64_t da, db;
        step_of(na, nb, rc, fs - 2, &da, &db);
        const int64_t lim = (int64_t)1 << 30;
        int64_t n2 = INT64_MAX, l = INT64_MAX;
        if (da < lim && da > -lim && db < lim && db > -lim) {
            n2 = da * da + db * db;
            l = da < 0 ? -da : da;
            if ((db < 0 ? -db : db) > l)
                l = db < 0 ? -db : db;
        }
        if (n2 <= ACC2) {
            a -= (int32_t)da;
            b -= (int32_t)db;
            *iterations += 1;
            *s_a = a;
            *s_b = b;
            return describe(g, a, b, &pt, limits, out);
        }
        const int contracts = l_prev > 0 && l < lim && 4 * l <= l_prev;
        if (contracts && l * l <= SETTLE_ACC * l_prev) {
            a -= (int32_t)da;
            b -= (int32_t)db;
            *iterations += 1;
            *s_a = a;
            *s_b = b;
            /* The evaluation there gives M for the checks, and F: a contraction that ends off a
             * root (towards a minimum of |F|) is told by its residual, as every other end. */
            eval_point(k, a, b, &pt);
            return describe(g, a, b, &pt, limits, out);
        }
        if (it == max_iter)
            return -1;
        if (n2 > g->step_max2) {
            /* Along the step's direction (na, nb) / det, step_max long. */
            const int sg = rc.neg ? -1 : 1;
            const int bn = fx_bits64(na) > fx_bits64(nb) ? fx_bits64(na) : fx_bits64(nb);
            const int ks = bn > 30 ? bn - 30 : 0;
            const int64_t xa = fx_shr(na, ks) * sg, xb = fx_shr(nb, ks) * sg;
            const int64_t len = (int64_t)fx_isqrt64((uint64_t)(xa * xa + xb * xb));
            if (len == 0)
                return -1;
            da = xa * g->step_max / len;
            db = xb * g->step_max / len;
            l = 0; /* a clipped step says nothing of convergence */
        }
        a -= (int32_t)da;
        b -= (int32_t)db;
        *iterations += 1;
        if (a > g->s_box || a < -g->s_box || b > g->s_box || b < -g->s_box)
            return -1;
        /* The next step a chord one while the steps are small and shrinking. */
        chord = l > 0 && l <= CHORD_REGIME && (l_prev == 0 || contracts);
        l_prev = l;
    }
}

static void consts_of(const tse_fx_geometry *g, const fx_local *loc, consts *k)
{
    k->u = loc->u;
    k->v = loc->v;
    k->u26 = loc->u26;
    k->v26 = loc->v26;
    k->k50 = loc->rho2 - fx_shl(g->L2, 2);
    k->k = fx_shr(k->k50, 2);
    k->g = g->g;
    k->c = g->c;
}

/* ---- The quartic in m = a + b (kinematics.md, "Notes for the solver"), in Q20. ----
 * With delta = u^2 - v^2, A = m^2 + delta, 2 m s_A = A + 2 u m, 2 m s_B = m^2 - delta + 2 v m:
 *   4 m^2 F2 = A^2 + 4 m^2 (K - u^2) - g [(2 m s_A)^2 + (2 m s_B)^2 + 2 c (2 m s_A)(2 m s_B)]
 * whose coefficients, from m^0 up:
 *   delta^2 (1 - 2 g (1 - c)),  -4 g delta (u - v)(1 - c),
 *   2 delta + 4 (K - u^2) - 4 g (u^2 + v^2 + 2 c u v),  -4 g (1 + c)(u + v),  1 - 2 g (1 + c).
 * Its real roots are isolated by those of its derivatives (each monotone between consecutive
 * critical points) and bisected; m ranges over what positive slides within the format's room give,
 * |m| <= 2 s_box + |u| + |v| (32 m: Q20 in 26 bits, P's terms within 64 bits through
 * fx_mul64x32). */
#define Q20_MUL(a, b) fx_shr((a) * (b), 20)

static int64_t poly_eval(const int64_t *c, int deg, int32_t m)
{
    int64_t p = c[deg];
    for (int j = deg - 1; j >= 0; --j)
        p = fx_mul64x32(p, m, 20) + c[j];
    return p;
}

static int sign64(int64_t x)
{
    return (x > 0) - (x < 0);
}

/* Roots of c (degree deg >= 1, monotone between the sorted critical points crit[0..nc-1]) in
 * [lo, hi]: up to deg of them, ascending, into roots. */
static int poly_roots(const int64_t *c, int deg, int32_t lo, int32_t hi, const int32_t *crit, int nc,
                      int32_t *roots)
{
    int32_t pts[6];
    int np = 0, n = 0;
    pts[np++] = lo;
    for (int j = 0; j < nc; ++j)
        if (crit[j] > lo && crit[j] < hi)
            pts[np++] = crit[j];
    pts[np++] = hi;
    for (int j = 0; j + 1 < np && n < deg; ++j) {
        int32_t a = pts[j], b = pts[j + 1];
        int sa = sign64(poly_eval(c, deg, a)), sb = sign64(poly_eval(c, deg, b));
        if (sa == 0) {
            if (n == 0 || roots[n - 1] != a)
                roots[n++] = a;
            continue;
        }
        if (sb == 0 || sa == sb)
            continue;
        while (b - a > 1) {
            const int32_t mid = a + (b - a) / 2;
            const int sm = sign64(poly_eval(c, deg, mid));
            if (sm == 0) {
                a = mid; /* the root itself: the bracket is done */
                break;
            }
            if (sm == sa)
                a = mid;
            else
                b = mid;
        }
        roots[n++] = a;
    }
    return n;
}

/* Every real root of the quartic in [lo, hi], and its critical points there (a double root that
 * only touches zero shows as one), as starting points for the polish: returns how many. */
static int quartic_candidates(const consts *k, int32_t lo, int32_t hi, int32_t *cand)
{
    const int64_t u = fx_shr(k->u, 4), v = fx_shr(k->v, 4);
    const int64_t g = fx_shr(k->g, 6), c = fx_shr(k->c, 10), one = (int64_t)1 << 20;
    const int64_t delta = Q20_MUL(u, u) - Q20_MUL(v, v), K = fx_shr(k->k, 28);
    int64_t P[5];
    P[0] = Q20_MUL(Q20_MUL(delta, delta), one - 2 * Q20_MUL(g, one - c));
    P[1] = -4 * Q20_MUL(Q20_MUL(Q20_MUL(g, delta), u - v), one - c);
    P[2] = 2 * delta + 4 * (K - Q20_MUL(u, u)) -
           4 * Q20_MUL(g, Q20_MUL(u, u) + Q20_MUL(v, v) + 2 * Q20_MUL(c, Q20_MUL(u, v)));
    P[3] = -4 * Q20_MUL(Q20_MUL(g, one + c), u + v);
    P[4] = one - 2 * Q20_MUL(g, one + c);
    const int64_t D1[4] = {P[1], 2 * P[2], 3 * P[3], 4 * P[4]};
    const int64_t D2[3] = {2 * P[2], 6 * P[3], 12 * P[4]};
    const int64_t D3[2] = {6 * P[3], 24 * P[4]};
    int32_t r3[1], r2[2], r1[3], r0[4];
    const int n3 = poly_roots(D3, 1, lo, hi, NULL, 0, r3);
    const int n2 = poly_roots(D2, 2, lo, hi, r3, n3, r2);
    const int n1 = poly_roots(D1, 3, lo, hi, r2, n2, r1);
    const int n0 = poly_roots(P, 4, lo, hi, r1, n1, r0);
    int n = 0;
    for (int j = 0; j < n0; ++j)
        cand[n++] = r0[j];
    for (int j = 0; j < n1; ++j)
        cand[n++] = r1[j];
    return n;
}

/* The slides of a root m (Q20) of the quartic: 2 m s_A = m^2 + 2 u m + delta, and s_B alike.
 * Returns 0 when m is zero or they leave the format's room. */
static int slides_of(const tse_fx_geometry *g, const consts *k, int32_t m20, int32_t *s_a, int32_t *s_b)
{
    const int64_t m = fx_shl(m20, 4); /* Q24 */
    if (m == 0)
        return 0;
    const int64_t delta = (int64_t)k->u * k->u - (int64_t)k->v * k->v;
    const int64_t a = fx_div(m * m + 2 * k->u * m + delta, 2 * m, 0);
    const int64_t b = fx_div(m * m + 2 * k->v * m - delta, 2 * m, 0);
    if (a > g->s_box || a < -g->s_box || b > g->s_box || b < -g->s_box)
        return 0;
    *s_a = (int32_t)a;
    *s_b = (int32_t)b;
    return 1;
}

static tse_status fallback(const tse_fx_geometry *g, const consts *k, int32_t seed_a, int32_t seed_b,
                           int iterations, fx_sol *out)
{
    const int32_t box = g->s_box >> 4; /* Q20 */
    const int32_t lo = -(k->u >> 4) - (k->v >> 4), hi = 2 * box + lo;
    int32_t cand[7];
    const int n = quartic_candidates(k, lo, hi, cand);
    int found = 0, best_in = 0;
    int64_t best_dist = 0;
    for (int r = 0; r < n; ++r) {
        int32_t a, b;
        if (!slides_of(g, k, cand[r], &a, &b))
            continue;
        fx_sol cs;
        int valid = newton(g, k, &a, &b, POLISH_MAX_ITER, 0, &iterations, &cs);
        if (valid < 0) {
            point pt;
            eval_point(k, a, b, &pt);
            valid = describe(g, a, b, &pt, 0, &cs);
        }
        if (!valid)
            continue;
        const int in = fx_within_limits(g, &cs);
        const int64_t dist = ((int64_t)a - seed_a) * ((int64_t)a - seed_a) + ((int64_t)b - seed_b) * ((int64_t)b - seed_b);
        if (found && a == out->s_a && b == out->s_b)
            continue;
        if (!found || (in && !best_in) || (in == best_in && dist < best_dist)) {
            *out = cs;
            best_in = in;
            best_dist = dist;
            found = 1;
        }
    }
    out->iterations = iterations;
    out->fallback = 1;
    return found ? TSE_OK : TSE_UNREACHABLE;
}

tse_status fx_scissor_solve(const tse_fx_geometry *g, const fx_local *loc, int32_t seed_a, int32_t seed_b,
                            fx_sol *out)
{
    int iterations = 0;
    out->iterations = 0;
    out->fallback = 0;
    if (loc->far) {
        out->fallback = 1;
        return TSE_UNREACHABLE;
    }
    consts k;
    consts_of(g, loc, &k);
    int32_t a = seed_a, b = seed_b;
    if (newton(g, &k, &a, &b, NEWTON_MAX_ITER, 1, &iterations, out) == 1) {
        out->iterations = iterations;
        out->fallback = 0;
        return TSE_OK;
    }
    return fallback(g, &k, seed_a, seed_b, iterations, out);
}
