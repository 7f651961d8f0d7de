/* The geometric path through the waypoints: a natural cubic spline in the six pose coordinates over
 * the chord length, or straight pieces with their corners blended (plan.h). */
#include <math.h>
#include <string.h>

#include "plan_internal.h"

static double wrap_angle(double a)
{
    a = fmod(a, 2.0 * PLAN_PI);
    if (a > PLAN_PI)
        a -= 2.0 * PLAN_PI;
    else if (a <= -PLAN_PI)
        a += 2.0 * PLAN_PI;
    return a;
}

/* Distance in the path's metric: position in metres, angles as r_top times radians. */
static double chord(const double a[6], const double b[6], double r_top)
{
    double d2 = 0.0;
    for (int k = 0; k < 6; ++k) {
        const double d = (b[k] - a[k]) * (k < 3 ? 1.0 : r_top);
        d2 += d * d;
    }
    return sqrt(d2);
}

/* Natural spline second derivatives at the knots (Thomas algorithm, all six coordinates at once;
 * m2 first holds the eliminated right-hand sides, the pieces' scratch the diagonal). */
static void spline_solve(plan_path *path, double *diag)
{
    const int n = path->n;
    const double *s = path->ws;
    double (*y)[6] = path->val, (*m)[6] = path->m2;
    memset(m, 0, (size_t)n * sizeof m[0]);
    if (n < 3)
        return;
    /* Unknowns M_1..M_{n-2}; M_0 = M_{n-1} = 0. */
    for (int i = 1; i < n - 1; ++i) {
        const double h0 = s[i] - s[i - 1], h1 = s[i + 1] - s[i];
        double b = 2.0 * (h0 + h1);
        double rhs[6];
        for (int k = 0; k < 6; ++k)
            rhs[k] = 6.0 * ((y[i + 1][k] - y[i][k]) / h1 - (y[i][k] - y[i - 1][k]) / h0);
        if (i > 1) {
            const double f = h0 / diag[i - 1];
            b -= f * h0;
            for (int k = 0; k < 6; ++k)
                rhs[k] -= f * m[i - 1][k];
        }
        diag[i] = b;
        for (int k = 0; k < 6; ++k)
            m[i][k] = rhs[k];
    }
    for (int i = n - 2; i >= 1; --i) {
        const double h1 = s[i + 1] - s[i];
        for (int k = 0; k < 6; ++k)
            m[i][k] = (m[i][k] - (i < n - 2 ? h1 * m[i + 1][k] : 0.0)) / diag[i];
    }
}

/* Straight pieces between the waypoints, each corner cut by a quadratic blend whose middle is at
 * most `blend` from the waypoint: control points W - l d1, W, W + l d2 put its middle
 * l |d2 - d1| / 4 from W, and its length along s is 2 l, so that the path's direction is continuous
 * in s at both ends. */
static void blend_build(plan_path *path, const plan_waypoint *wp, double blend)
{
    const int n = path->n;
    const double (*y)[6] = (const double (*)[6])path->val;
    double *cut = (double *)path->m2; /* l at each waypoint (scratch: the blend needs no m2) */
    for (int i = 0; i < n; ++i) {
        cut[i] = 0.0;
        if (i == 0 || i == n - 1)
            continue;
        const double la = chord(y[i - 1], y[i], path->r_top), lb = chord(y[i], y[i + 1], path->r_top);
        double dd = 0.0;
        for (int k = 0; k < 6; ++k) {
            const double w = k < 3 ? 1.0 : path->r_top;
            const double d = w * ((y[i + 1][k] - y[i][k]) / lb - (y[i][k] - y[i - 1][k]) / la);
            dd += d * d;
        }
        dd = sqrt(dd);
        if (dd > 1e-12)
            cut[i] = fmin(4.0 * blend / dd, 0.5 * fmin(la, lb));
    }
    (void)wp;
    int np = 0;
    double s = 0.0;
    for (int i = 0; i + 1 < n; ++i) {
        const double l = chord(y[i], y[i + 1], path->r_top);
        /* The straight piece between the blends at each end. */
        const double a = cut[i] / l, b = 1.0 - cut[i + 1] / l;
        if (i == 0)
            path->ws[0] = 0.0;
        if (b - a > 1e-12) {
            plan_piece *pc = &path->pieces[np++];
            pc->blend = false;
            pc->s0 = s;
            pc->len = (b - a) * l;
            for (int k = 0; k < 6; ++k) {
                pc->p0[k] = y[i][k] + a * (y[i + 1][k] - y[i][k]);
                pc->p1[k] = y[i][k] + b * (y[i + 1][k] - y[i][k]);
            }
            s += pc->len;
        }
        if (i + 1 == n - 1) {
            path->ws[i + 1] = s;
            break;
        }
        const double l2 = chord(y[i + 1], y[i + 2], path->r_top);
        if (cut[i + 1] > 0.0) {
            plan_piece *pc = &path->pieces[np++];
            pc->blend = true;
            pc->s0 = s;
            pc->len = 2.0 * cut[i + 1];
            for (int k = 0; k < 6; ++k) {
                pc->p0[k] = y[i + 1][k] - cut[i + 1] * (y[i + 1][k] - y[i][k]) / l;
                pc->p1[k] = y[i + 1][k];
                pc->p2[k] = y[i + 1][k] + cut[i + 1] * (y[i + 2][k] - y[i + 1][k]) / l2;
            }
            path->ws[i + 1] = s + cut[i + 1]; /* the blend's middle: nearest the corner */
            s += pc->len;
        } else {
            path->ws[i + 1] = s;
        }
    }
    path->n_pieces = np;
    path->length = s;
}

int plan_path_build(plan_path *path, const plan_waypoint *wp, int n, double blend, plan_result *r)
{
    path->n = n;
    for (int i = 0; i < n; ++i) {
        for (int k = 0; k < 6; ++k)
            path->val[i][k] = wp[i].pose[k];
        /* Angles continue from the previous waypoint's the short way (yaw 3.1 then -3.1 turns 0.08). */
        for (int k = 3; k < 6 && i > 0; ++k)
            path->val[i][k] = path->val[i - 1][k] + wrap_angle(wp[i].pose[k] - wp[i - 1].pose[k]);
        path->ws[i] = i ? path->ws[i - 1] + chord(path->val[i - 1], path->val[i], path->r_top) : 0.0;
        if (i > 0 && !(path->ws[i] - path->ws[i - 1] > 1e-9)) {
            r->status = PLAN_BAD_INPUT;
            r->waypoint = i;
            r->why = "repeats the waypoint before it (the path must move between waypoints)";
            return -1;
        }
    }
    path->length = path->ws[n - 1];
    path->n_pieces = 0;
    if (blend > 0.0)
        blend_build(path, wp, blend);
    else
        spline_solve(path, (double *)path->pieces);
    return 0;
}

long plan_interval(const double *a, long n, double x)
{
    long lo = 0, hi = n - 1;
    while (hi - lo > 1) {
        const long mid = (lo + hi) / 2;
        if (a[mid] <= x)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

static void spline_eval(const plan_path *path, double s, double p[6], double dp[6], double ddp[6])
{
    const double *ws = path->ws;
    const long lo = plan_interval(ws, path->n, s), hi = lo + 1;
    const double h = ws[hi] - ws[lo];
    const double A = (ws[hi] - s) / h, B = 1.0 - A;
    const double *y0 = path->val[lo], *y1 = path->val[hi], *m0 = path->m2[lo], *m1 = path->m2[hi];
    for (int k = 0; k < 6; ++k) {
        p[k] = A * y0[k] + B * y1[k] + ((A * A * A - A) * m0[k] + (B * B * B - B) * m1[k]) * h * h / 6.0;
        if (dp)
            dp[k] = (y1[k] - y0[k]) / h - (3.0 * A * A - 1.0) / 6.0 * h * m0[k] + (3.0 * B * B - 1.0) / 6.0 * h * m1[k];
        if (ddp)
            ddp[k] = A * m0[k] + B * m1[k];
    }
}

static void blend_eval(const plan_path *path, double s, double p[6], double dp[6], double ddp[6])
{
    int lo = 0, hi = path->n_pieces;
    while (hi - lo > 1) {
        const int mid = (lo + hi) / 2;
        if (path->pieces[mid].s0 <= s)
            lo = mid;
        else
            hi = mid;
    }
    const plan_piece *pc = &path->pieces[lo];
    const double u = fmin(fmax((s - pc->s0) / pc->len, 0.0), 1.0);
    for (int k = 0; k < 6; ++k) {
        if (!pc->blend) {
            p[k] = pc->p0[k] + u * (pc->p1[k] - pc->p0[k]);
            if (dp)
                dp[k] = (pc->p1[k] - pc->p0[k]) / pc->len;
            if (ddp)
                ddp[k] = 0.0;
        } else {
            const double a = pc->p0[k], b = pc->p1[k], c = pc->p2[k];
            p[k] = (1 - u) * (1 - u) * a + 2 * u * (1 - u) * b + u * u * c;
            if (dp)
                dp[k] = (2 * (1 - u) * (b - a) + 2 * u * (c - b)) / pc->len;
            if (ddp)
                ddp[k] = 2 * (a - 2 * b + c) / (pc->len * pc->len);
        }
    }
}

void plan_path_eval(const plan_path *path, double s, double p[6], double dp[6], double ddp[6])
{
    s = fmin(fmax(s, 0.0), path->length);
    if (path->n_pieces > 0)
        blend_eval(path, s, p, dp, ddp);
    else
        spline_eval(path, s, p, dp, ddp);
    for (int k = 3; k < 6; ++k)
        p[k] = wrap_angle(p[k]);
}
