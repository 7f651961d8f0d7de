/* A jerk-limited time law from the time-optimal one: its path speed averaged over a window Tj,
 *     s~'(t) = (s(t) - s(t - Tj)) / Tj,   s~(t) = (1 / Tj) integral over [t - Tj, t] of s,
 * with s at rest at 0 before the motion and at the path's end L after it.  The smoothed law's
 * acceleration s~'' = (s'(t) - s'(t - Tj)) / Tj is an average of the law's, and its jerk is
 * (s''(t) - s''(t - Tj)) / Tj: a slide whose acceleration (mostly q_s s'') stays within A turns
 * it at most by 2 A within Tj (plan_jerk_smooth chooses Tj).  Where the law accelerates or brakes
 * at A for longer than Tj the result is the usual jerk-limited ramp (its acceleration rising over
 * Tj); the motion lasts Tj longer, and its speed at a point is the average of the law's over the
 * stretch just behind, so it stays within the speed limits wherever they do not dip within a
 * window (the validator slows what it refuses, as for any plan).
 *
 * The new law is written back on the same grid: at each point s_j the time t_j where s~ reaches
 * it (a safeguarded Newton on s~, whose derivative is s~'), and x_j = s~'(t_j)^2; between two
 * points the law follows the cubic through their places and speeds (time_law.c). */
#include <math.h>

#include "plan_internal.h"

typedef struct {
    const plan_grid *gr;
    const double *I; /* the integral of s over [0, t_i] at each point */
    long hint;       /* the interval last found */
} law;

/* s, s', s'' and the integral of s at time t of the unsmoothed law (constant s'' in an interval). */
static void law_at(law *w, double t, double out[4])
{
    const plan_grid *gr = w->gr;
    const double L = (double)gr->N * gr->h, T = gr->t[gr->N];
    if (t <= 0.0) {
        out[0] = out[1] = out[2] = out[3] = 0.0;
        return;
    }
    if (t >= T) {
        out[0] = L;
        out[1] = out[2] = 0.0;
        out[3] = w->I[gr->N] + L * (t - T);
        return;
    }
    long i = w->hint;
    while (i + 1 < gr->N && gr->t[i + 1] <= t)
        ++i;
    while (i > 0 && gr->t[i] > t)
        --i;
    w->hint = i;
    const double tau = t - gr->t[i], v0 = sqrt(gr->x[i]), u = (gr->x[i + 1] - gr->x[i]) / (2.0 * gr->h);
    const double s0 = (double)i * gr->h;
    out[0] = s0 + v0 * tau + 0.5 * u * tau * tau;
    out[1] = v0 + u * tau;
    out[2] = u;
    out[3] = w->I[i] + s0 * tau + 0.5 * v0 * tau * tau + u * tau * tau * tau / 6.0;
}

/* The smoothed law at time t: its place, speed, acceleration and jerk along the path. */
static void smooth_at(law *now, law *back, double tj, double t, double out[4])
{
    double a[4], b[4];
    law_at(now, t, a);
    law_at(back, t - tj, b);
    out[0] = (a[3] - b[3]) / tj;
    out[1] = (a[0] - b[0]) / tj;
    out[2] = (a[1] - b[1]) / tj;
    out[3] = (a[2] - b[2]) / tj;
}

/* The law smoothed over tj into xs and ts; returns the greatest slide jerk it has at a grid point
 * from the path's own jerk and the Jacobian's change along it: q_s j + 3 q_ss v a. */
static double smooth_once(plan *p, double tj)
{
    plan_grid *gr = &p->grid;
    const long N = gr->N;
    const double T = gr->t[N];
    law now = {gr, gr->K, 0}, back = {gr, gr->K, 0};
    gr->xs[0] = gr->xs[N] = 0.0;
    gr->ts[0] = 0.0;
    gr->ts[N] = T + tj;
    double lo = 0.0, worst = 0.0;
    for (long j = 1; j < N; ++j) {
        const double want = (double)j * gr->h;
        double hi = T + tj, t = lo, f[4];
        smooth_at(&now, &back, tj, t, f);
        for (int it = 0; it < 100 && hi - lo > 1e-13 * (T + tj); ++it) {
            if (f[0] < want)
                lo = t;
            else
                hi = t;
            if (fabs(f[0] - want) <= 1e-12 * gr->h)
                break;
            double next = f[1] > 0.0 ? t + (want - f[0]) / f[1] : 0.5 * (lo + hi);
            if (!(next > lo && next < hi))
                next = 0.5 * (lo + hi); /* Newton left the bracket: bisect */
            t = next;
            smooth_at(&now, &back, tj, t, f);
        }
        gr->xs[j] = f[1] * f[1];
        gr->ts[j] = t;
        lo = t;
        for (int k = 0; k < 6; ++k)
            worst = fmax(worst, fabs(gr->qs[j][k] * f[3] + 3.0 * gr->qss[j][k] * f[1] * f[2]));
    }
    return worst;
}

void plan_jerk_smooth(plan *p)
{
    plan_grid *gr = &p->grid;
    const long N = gr->N;
    /* The integral of s, point by point (scratch: K, which the next law computes afresh). */
    double *I = gr->K;
    I[0] = 0.0;
    for (long i = 0; i < N; ++i) {
        const double d = gr->t[i + 1] - gr->t[i], v0 = sqrt(gr->x[i]), u = (gr->x[i + 1] - gr->x[i]) / (2.0 * gr->h);
        I[i + 1] = I[i] + (double)i * gr->h * d + 0.5 * v0 * d * d + u * d * d * d / 6.0;
    }
    /* A window of A / J turns a slide's acceleration from 0 to A (or from A to 0) at J: the usual
     * jerk-limited ramp, the motion A / J longer than without.  Where the law turns from
     * accelerating to braking at once (a short move, a dip of the speed limit) it turns by up to
     * 2 A within the window: the window widens until the jerk is within the limit, to 2 A / J at
     * most, which holds for any law within A. */
    const double wide = 2.0 * p->alim / p->jmax;
    double tj = p->alim / p->jmax;
    for (int round = 0;; ++round) {
        const double worst = smooth_once(p, tj);
        if (worst <= p->jmax || tj >= wide)
            break;
        tj = round < 3 ? fmin(wide, tj * fmax(worst / p->jmax, 1.05)) : wide;
    }
    p->tj = tj;
    for (long j = 0; j <= N; ++j) {
        gr->x[j] = gr->xs[j];
        gr->t[j] = gr->ts[j];
    }
}
