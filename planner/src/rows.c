/* The rows of a plan: first a row holding the first waypoint traj_lead after the start (plan.h says
 * why; a file of rows also says so where it starts: tse-kin check judges it from rest at its first
 * row); then,
 * from there, a row at the time each waypoint is passed (the controller runs straight between rows,
 * so a row there keeps its path through the waypoint), and between two of them the fewest rows
 * evenly spaced at most a period apart.  Even spacing keeps every row at least half a period long
 * (a short row would turn the wire's micrometre rounding into a speed change the validator sees)
 * and none longer than a period (the time law's acceleration assumes that much).  Rows a period
 * or less apart show the validator a slide's acceleration as it is only when its stride is a
 * whole number of rows: in between, its three samples fall at different places between rows, where
 * the straight rows cut inside the curve by up to a P'^2 / 8, and it sees up to 12 % more (rows
 * 7 ms apart against its 10 ms).  So there a stretch takes more rows (up to twice as many) until
 * their spacing is one the stride sees within half a per cent.  No two rows are closer than the
 * controller's queue allows (plan.h, plan_row_spacing_min): a waypoint passed sooner after the one before
 * (or before the last) has no row of its own.  Times in
 * whole microseconds, as the wire carries them. */
#include <math.h>
#include <string.h>

#include "plan_internal.h"

/* The waypoint whose row ends the stretch from waypoint a's: the first whose row is the queue's
 * least spacing or more after a's (and before the last's), passing on to later ones while the span
 * is over a period but under twice that spacing (its two rows would be closer than it). */
static int stretch_end(const plan *p, int a)
{
    const int final = p->n - 1;
    const int64_t min = p->min_us, t0 = p->tw_us[a];
    int b = a + 1;
    while (b < final) {
        const int64_t span = p->tw_us[b] - t0;
        if (span >= min && !(span > p->period_us && span < 2 * min) && p->tw_us[final] - p->tw_us[b] >= min)
            break;
        ++b;
    }
    return b;
}

/* What the validator's acceleration, a second difference over stride S of samples of rows P apart
 * (straight between them), makes of a constant acceleration, at worst over where the rows fall:
 * 1 + max (e1 - 2 e2 + e3) / S^2, with e = tau (P - tau) / 2 the straight row's gap at phase tau. */
static double stride_factor(double P, double S)
{
    double worst = 0.0;
    for (int i = 0; i < 64; ++i) {
        const double t1 = P * i / 64.0, t2 = fmod(t1 - S + 2.0 * S, P), t3 = fmod(t1 - 2.0 * S + 3.0 * S, P);
        const double e1 = t1 * (P - t1), e2 = t2 * (P - t2), e3 = t3 * (P - t3);
        worst = fmax(worst, 0.5 * (e1 - 2.0 * e2 + e3) / (S * S));
    }
    return 1.0 + worst;
}

static void stretch_begin(const plan *p, plan_cursor *c, int a)
{
    c->a = a;
    c->b = stretch_end(p, a);
    const int64_t span = p->tw_us[c->b] - p->tw_us[a];
    /* At most a period apart, evenly: with the stretch's span over a period at least twice the
     * queue's least spacing, no row is closer than that either. */
    const int64_t by_period = (span + p->period_us - 1) / p->period_us, by_min = span / p->min_us;
    const int64_t by_wire = span / PLAN_ROW_MIN_US;
    c->m = by_period < by_wire ? by_period : by_wire;
    if (c->m < 1)
        c->m = 1;
    const double stride_us = 1e6 * FW_ACC_STRIDE / (double)p->lim.segment_hz;
    if ((double)p->period_us <= stride_us) {
        long best = c->m;
        double best_f = stride_factor((double)span / (double)c->m, stride_us);
        for (long m = c->m + 1; m <= 2 * c->m && m <= by_min && best_f > 1.005; ++m) {
            const double f = stride_factor((double)span / (double)m, stride_us);
            if (f < best_f) {
                best = m;
                best_f = f;
            }
        }
        c->m = best;
    }
    c->j = 1;
}

void plan_rows_begin(const plan *p, plan_cursor *c)
{
    c->held = false;
    c->done = false;
    stretch_begin(p, c, 0);
}

int plan_rows_next(const plan *p, plan_cursor *c, plan_row *row)
{
    if (!c->held) {
        c->held = true;
        row->t = (double)p->hold_us * 1e-6;
        memcpy(row->pose, p->wp[0].pose, sizeof row->pose);
        return 1;
    }
    if (c->done)
        return 0;
    const int64_t t0 = p->tw_us[c->a], span = p->tw_us[c->b] - t0;
    const int64_t t = c->j == c->m ? p->tw_us[c->b] : t0 + (span * c->j + c->m / 2) / c->m;
    row->t = (double)(t + p->hold_us) * 1e-6;
    if (c->j == c->m && c->b == p->n - 1) {
        c->done = true;
        plan_path_eval(&p->path, p->path.length, row->pose, NULL, NULL);
        return 1;
    }
    plan_pose_at(p, (double)t * 1e-6, row->pose);
    if (c->j == c->m)
        stretch_begin(p, c, c->b);
    else
        ++c->j;
    return 1;
}

double plan_duration(const plan *p)
{
    return (double)(p->tw_us[p->n - 1] + p->hold_us) * 1e-6;
}

long plan_row_count(const plan *p)
{
    return p->rows;
}

int plan_retries(const plan *p)
{
    return p->retries;
}

void plan_start_slides(const plan *p, double q[6])
{
    memcpy(q, p->q0, sizeof p->q0);
}

int plan_row_waypoint(const plan *p, double t)
{
    const int64_t at = llround(t * 1e6) - p->hold_us;
    int w = 0;
    while (w + 1 < p->n && p->tw_us[w + 1] <= at)
        ++w;
    return w;
}

double plan_hold(const plan *p)
{
    return (double)p->hold_us * 1e-6;
}
