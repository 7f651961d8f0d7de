/* The time law along the path by reachability (TOPP-RA, Pham and Pham 2018), on the grid.
 *
 * State x = s'^2, control u = s''; over a grid step h with u constant, x' = x + 2 h u.  At a grid
 * point the slides move at q' = q_s s' and accelerate at q'' = q_s u + q_ss x, so each slide's
 * speed limit bounds x alone (x <= (V / |q_s|)^2) and its acceleration limit is two half-planes
 * in (x, u).  Backward from rest at the end, K_i is the greatest x at point i from which some
 * admissible u reaches [0, K_{i+1}]; the admissible x at a point are an interval holding 0 (u = 0
 * holds every slide at rest there), so a bisection finds K_i.  Forward from rest at the start, each
 * step takes the greatest admissible u that keeps x within K: the time-optimal law on the grid. */
#include <math.h>

#include "plan_internal.h"

/* Bounds on u at grid point i with x, under the limits there.  Returns false when no u is
 * admissible (x beyond what the accelerations allow with the slides' curvature).
 *
 * Rows further apart than the validator's stride S show a slide's acceleration unevenly: the
 * change of the plate's own velocity comes at the rows, where the stride sees a row's change whole
 * (P / S times the acceleration), while the part of q'' that comes from the Jacobian's change
 * (q_sj x) bends each straight row evenly and is seen as it is.  So with f = min(1, S / P) the
 * limit on f (P / S)(q_s u + (q_ss - q_sj) x) + q_sj x is f A on q_s u + (q_ss - q_sj + f q_sj) x
 * (p->alim holds f A; at P <= S it is q'' itself). */
static bool u_bounds(const plan *p, long i, double x, double *lo, double *hi)
{
    const plan_grid *gr = &p->grid;
    const double k = gr->slow[i] * p->pace[gr->stretch[i]];
    const double A = p->alim * k * k;
    double l = -INFINITY, u = INFINITY;
    for (int j = 0; j < 6; ++j) {
        const double a = gr->qs[i][j], b = (gr->qss[i][j] - (1.0 - p->row_f) * gr->qsj[i][j]) * x;
        if (fabs(a) < 1e-9) {
            if (fabs(b) > A)
                return false;
            continue;
        }
        const double u1 = (-A - b) / a, u2 = (A - b) / a;
        l = fmax(l, fmin(u1, u2));
        u = fmin(u, fmax(u1, u2));
    }
    *lo = l;
    *hi = u;
    return l <= u;
}

/* The greatest x the speed limits (and the plate speed cap) allow at point i.  The controller runs
 * straight in pose between rows, and along a straight line a slide's speed changes as the Jacobian
 * does: over a row `period` long, by q_sj x period from one end to the other, so at an end it is
 * up to half that above the speed at the row's middle.  Each slide is held to
 * |q_s| s' + |q_sj| s'^2 period / 2 <= V, a quadratic in s' (its root in the stable form). */
static double x_speed(const plan *p, long i)
{
    const plan_grid *gr = &p->grid;
    const double V = p->vlim * gr->slow[i] * p->pace[gr->stretch[i]];
    double x = gr->vcap2[i];
    for (int j = 0; j < 6; ++j) {
        const double a = fabs(gr->qs[i][j]), c = 0.5 * p->opt.period * fabs(gr->qsj[i][j]);
        if (a > 1e-12 || c > 1e-12) {
            const double y = 2.0 * V / (a + sqrt(a * a + 4.0 * c * V));
            x = fmin(x, y * y);
        }
    }
    return x;
}

/* Whether from x at point i some admissible u reaches [0, k_next] at point i + 1. */
static bool reaches(const plan *p, long i, double x, double k_next)
{
    double lo, hi;
    if (!u_bounds(p, i, x, &lo, &hi))
        return false;
    const double h2 = 2.0 * p->grid.h;
    return fmax(lo, -x / h2) <= fmin(hi, (k_next - x) / h2);
}

/* After smoothing: where the smoothed law is faster than the speed limits allow (its speed at a
 * point is the average of the law's over the stretch the window covers, where a slide may be
 * faster for the same path speed), caps the law's speed over that stretch at its present speeds
 * scaled down by the excess, for the next round.  Returns whether it capped any. */
static bool capped_where_too_fast(plan *p)
{
    plan_grid *gr = &p->grid;
    bool any = false;
    /* The law is planned within v_margin of the speed limits, which the smoothing may take. */
    const double room = 1.0 / (p->opt.v_margin * p->opt.v_margin);
    for (long i = 1; i < gr->N; ++i) {
        const double lim = x_speed(p, i);
        if (!(gr->x[i] > lim * room))
            continue;
        const double reach = sqrt(gr->x[i]) * p->tj / gr->h;
        const long w = reach < (double)gr->N ? (long)ceil(reach) : gr->N;
        const double scale = lim / gr->x[i] * (1.0 - 1e-3);
        for (long k = i > w ? i - w : 0; k <= i + w && k <= gr->N; ++k)
            gr->cap[k] = fmin(gr->cap[k], fmax(gr->x[k] * scale, 0.0));
        any = true;
    }
    return any;
}

static void backward(plan *p)
{
    plan_grid *gr = &p->grid;
    gr->K[gr->N] = 0.0;
    for (long i = gr->N - 1; i >= 0; --i) {
        double hi = fmin(x_speed(p, i), gr->cap[i]);
        if (!isfinite(hi)) /* no slide moves along the path here: bounded by the next point's reach */
            hi = gr->K[i + 1] + 1.0;
        if (reaches(p, i, hi, gr->K[i + 1])) {
            gr->K[i] = hi;
            continue;
        }
        double lo = 0.0;
        for (int it = 0; it < 60 && hi - lo > 1e-12 * hi; ++it) {
            const double mid = 0.5 * (lo + hi);
            if (reaches(p, i, mid, gr->K[i + 1]))
                lo = mid;
            else
                hi = mid;
        }
        gr->K[i] = lo;
    }
}

static void forward(plan *p)
{
    plan_grid *gr = &p->grid;
    const double h2 = 2.0 * gr->h;
    gr->x[0] = 0.0;
    for (long i = 0; i < gr->N; ++i) {
        const double x = gr->x[i];
        double lo, hi;
        if (!u_bounds(p, i, x, &lo, &hi))
            hi = lo = 0.0; /* only by rounding at the bisection's edge */
        double u = fmin(hi, (gr->K[i + 1] - x) / h2);
        u = fmax(u, -x / h2);
        gr->x[i + 1] = fmin(fmax(x + h2 * u, 0.0), gr->K[i + 1]);
    }
}

/* How far past grid point i the law is tau into its interval: the cubic through both ends' places
 * and speeds (Hermite).  For the time-optimal law, whose acceleration is constant over an interval
 * and whose times are 2 h / (v_i + v_i+1) apart, it is that parabola itself; for a smoothed one
 * (plan_jerk_smooth) it follows its speeds, which a parabola would not (a jerk-limited start is
 * a cubic in time). */
static double along(const plan_grid *gr, long i, double tau)
{
    const double D = gr->t[i + 1] - gr->t[i];
    if (!(D > 0.0))
        return 0.0;
    const double th = fmin(fmax(tau / D, 0.0), 1.0), v0 = sqrt(gr->x[i]) * D, v1 = sqrt(gr->x[i + 1]) * D;
    const double d = gr->h * th * th * (3.0 - 2.0 * th) + v0 * th * (1.0 - th) * (1.0 - th) - v1 * th * th * (1.0 - th);
    return fmin(fmax(d, 0.0), gr->h);
}

/* Time from grid point i to s (in its interval): along() inverted, by bisection. */
static double time_in(const plan_grid *gr, long i, double d)
{
    if (d <= 0.0)
        return 0.0;
    double lo = 0.0, hi = gr->t[i + 1] - gr->t[i];
    for (int it = 0; it < 60 && hi - lo > 1e-12; ++it) {
        const double mid = 0.5 * (lo + hi);
        if (along(gr, i, mid) < d)
            lo = mid;
        else
            hi = mid;
    }
    return 0.5 * (lo + hi);
}

/* The times of the grid points under the law x (constant acceleration between two). */
static int times(plan_grid *gr, plan_result *r)
{
    gr->t[0] = 0.0;
    for (long i = 0; i < gr->N; ++i) {
        const double sum = sqrt(gr->x[i]) + sqrt(gr->x[i + 1]);
        if (!(sum > 0.0)) {
            r->status = PLAN_BAD_INPUT;
            r->waypoint = -1;
            r->why = "the path cannot move at some point (no admissible speed)";
            return -1;
        }
        gr->t[i + 1] = gr->t[i] + 2.0 * gr->h / sum;
    }
    return 0;
}

int plan_time_law(plan *p, plan_result *r)
{
    plan_grid *gr = &p->grid;
    for (long i = 0; i <= gr->N; ++i)
        gr->cap[i] = INFINITY;
    for (int round = 0;; ++round) {
        backward(p);
        forward(p);
        if (times(gr, r) != 0)
            return -1;
        if (!(p->jmax > 0.0))
            break;
        plan_jerk_smooth(p);
        if (round == 5 || !capped_where_too_fast(p))
            break;
    }
    for (int w = 0; w < p->n; ++w) {
        const double s = p->path.ws[w];
        long i = (long)(s / gr->h);
        if (i >= gr->N)
            i = gr->N - 1;
        const double t = w == p->n - 1 ? gr->t[gr->N] : w == 0 ? 0.0 : gr->t[i] + time_in(gr, i, s - (double)i * gr->h);
        p->tw_us[w] = llround(t * 1e6);
    }
    /* A path shorter than the wire's least dt still ends on a row of its own. */
    if (p->tw_us[p->n - 1] < p->min_us)
        p->tw_us[p->n - 1] = p->min_us;
    plan_cursor c;
    plan_row row;
    p->rows = 0;
    for (plan_rows_begin(p, &c); plan_rows_next(p, &c, &row);)
        ++p->rows;
    return 0;
}

void plan_pose_at(const plan *p, double t, double pose[6])
{
    const plan_grid *gr = &p->grid;
    if (t >= gr->t[gr->N]) {
        plan_path_eval(&p->path, p->path.length, pose, NULL, NULL);
        return;
    }
    const long lo = plan_interval(gr->t, gr->N + 1, t);
    plan_path_eval(&p->path, (double)lo * gr->h + along(gr, lo, t - gr->t[lo]), pose, NULL, NULL);
}
