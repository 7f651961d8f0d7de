/* Real roots of a polynomial of degree <= 4 that cannot be missed: the roots of the derivative
 * split the line into intervals on which the polynomial is monotonic, so each holds at most one
 * root, found by bisection safeguarding Newton.  Works in tse_real, no complex arithmetic. */
#include "kin_internal.h"

enum { TSE_POLY_MAX_DEG = 4 };

static tse_real horner(const tse_real *c, int deg, tse_real x, tse_real *dp)
{
    tse_real p = c[deg], d = TSE_R(0.0);
    for (int k = deg - 1; k >= 0; --k) {
        d = d * x + p;
        p = p * x + c[k];
    }
    *dp = d;
    return p;
}

/* Root of a polynomial that is monotonic on [lo, hi] with p(lo), p(hi) of opposite signs. */
static tse_real bracketed_root(const tse_real *c, int deg, tse_real lo, tse_real hi, tse_real plo)
{
    tse_real x = TSE_R(0.5) * (lo + hi);
    for (int it = 0; it < 200; ++it) {
        tse_real dp;
        const tse_real p = horner(c, deg, x, &dp);
        if (p == TSE_R(0.0))
            return x;
        if ((p < TSE_R(0.0)) == (plo < TSE_R(0.0)))
            lo = x;
        else
            hi = x;
        tse_real next = x - p / dp;
        /* Newton is taken only while it stays strictly inside the bracket. */
        if (!(next > lo && next < hi))
            next = TSE_R(0.5) * (lo + hi);
        if (next == x || hi - lo <= TSE_REAL_EPS * (tse_fabs(lo) + tse_fabs(hi)))
            return next;
        x = next;
    }
    return x;
}

static void sort_ascending(tse_real *x, int n)
{
    for (int i = 1; i < n; ++i) {
        const tse_real v = x[i];
        int j = i - 1;
        while (j >= 0 && x[j] > v) {
            x[j + 1] = x[j];
            --j;
        }
        x[j + 1] = v;
    }
}

static int quadratic_roots(const tse_real *coef, tse_real *roots)
{
    const tse_real a = coef[2], b = coef[1], c = coef[0];
    const tse_real disc = b * b - TSE_R(4.0) * a * c;
    if (disc < TSE_R(0.0))
        return 0;
    /* The cancellation-free form of the quadratic formula. */
    const tse_real q = TSE_R(-0.5) * (b + (b >= TSE_R(0.0) ? tse_sqrt(disc) : -tse_sqrt(disc)));
    if (q == TSE_R(0.0)) {
        roots[0] = TSE_R(0.0);
        roots[1] = TSE_R(0.0);
        return 2;
    }
    roots[0] = q / a;
    roots[1] = c / q;
    sort_ascending(roots, 2);
    return 2;
}

/* Roots of a polynomial of degree >= 3 given the real roots of its derivative. */
static int roots_between_critical_points(const tse_real *coef, int deg, const tse_real *crit, int ncrit,
                                         tse_real *roots)
{
    /* Cauchy's bound: every root lies within 1 + max |c_k / c_deg|. */
    tse_real bound = TSE_R(0.0);
    for (int k = 0; k < deg; ++k) {
        const tse_real r = tse_fabs(coef[k] / coef[deg]);
        if (r > bound)
            bound = r;
    }
    bound += TSE_R(1.0);

    tse_real edge[TSE_POLY_MAX_DEG + 1];
    int nedge = 0;
    edge[nedge++] = -bound;
    for (int k = 0; k < ncrit; ++k)
        if (crit[k] > -bound && crit[k] < bound)
            edge[nedge++] = crit[k];
    edge[nedge++] = bound;

    int n = 0;
    tse_real dummy;
    tse_real plo = horner(coef, deg, edge[0], &dummy);
    for (int k = 0; k + 1 < nedge; ++k) {
        const tse_real lo = edge[k], hi = edge[k + 1];
        const tse_real phi = horner(coef, deg, hi, &dummy);
        if (plo == TSE_R(0.0)) {
            if (n == 0 || roots[n - 1] != lo)
                roots[n++] = lo;
        } else if ((plo < TSE_R(0.0)) != (phi < TSE_R(0.0)) && phi != TSE_R(0.0)) {
            roots[n++] = bracketed_root(coef, deg, lo, hi, plo);
        } else if (k + 1 < nedge - 1) {
            /* A critical point that only touches zero is a double root; accept a near touch. */
            tse_real scale = TSE_R(0.0), xp = TSE_R(1.0);
            for (int j = 0; j <= deg; ++j) {
                scale += tse_fabs(coef[j]) * xp;
                xp *= tse_fabs(hi);
            }
            if (tse_fabs(phi) <= TSE_R(16.0) * TSE_REAL_EPS * scale)
                roots[n++] = hi;
        }
        plo = phi;
    }
    if (plo == TSE_R(0.0) && (n == 0 || roots[n - 1] != edge[nedge - 1]))
        roots[n++] = edge[nedge - 1];
    return n;
}

int tse_poly_real_roots(const tse_real *coef, int deg, tse_real *roots)
{
    if (deg < 1 || deg > TSE_POLY_MAX_DEG)
        return 0;
    if (deg == 1) {
        roots[0] = -coef[0] / coef[1];
        return isfinite(roots[0]) ? 1 : 0;
    }
    /* The derivative chain, highest derivative first: the roots of each derivative isolate the
     * roots of the polynomial below it. */
    tse_real chain[TSE_POLY_MAX_DEG - 1][TSE_POLY_MAX_DEG + 1] = {{TSE_R(0.0)}};
    for (int k = 0; k <= deg; ++k)
        chain[0][k] = coef[k];
    for (int level = 1; level <= deg - 2; ++level)
        for (int k = 1; k <= deg - level + 1; ++k)
            chain[level][k - 1] = (tse_real)k * chain[level - 1][k];

    tse_real crit[TSE_POLY_MAX_DEG], found[TSE_POLY_MAX_DEG];
    int ncrit = quadratic_roots(chain[deg - 2], crit);
    for (int level = deg - 3; level >= 0; --level) {
        const int n = roots_between_critical_points(chain[level], deg - level, crit, ncrit, found);
        for (int k = 0; k < n; ++k)
            crit[k] = found[k];
        ncrit = n;
    }
    for (int k = 0; k < ncrit; ++k)
        roots[k] = crit[k];
    return ncrit;
}
