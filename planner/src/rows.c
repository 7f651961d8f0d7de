/* The rows of a plan: first a row holding the first waypoint PLAN_HOLD_US after the start (so that
 * a file of rows says where it starts: tse-kin check judges it from rest at its first row), then,
 * from there, one every period, and one at the time each waypoint is passed (the controller runs straight between rows, so a row there keeps its path through the
 * waypoint); a regular row closer than the wire's least dt to a waypoint's gives way to it, and so
 * does a waypoint's to the next waypoint's.  Times in whole microseconds, as the wire carries them. */
#include <math.h>
#include <string.h>

#include "plan_internal.h"

void plan_rows_begin(const plan *p, plan_cursor *c)
{
    (void)p;
    c->k = 1;
    c->w = 1;
    c->last = 0;
    c->done = false;
    c->held = false;
}

int plan_rows_next(const plan *p, plan_cursor *c, plan_row *row)
{
    const int64_t min = PLAN_ROW_MIN_US;
    const int final = p->n - 1;
    if (!c->held) {
        c->held = true;
        row->t = (double)PLAN_HOLD_US * 1e-6;
        memcpy(row->pose, p->wp[0].pose, sizeof row->pose);
        return 1;
    }
    while (!c->done) {
        const int64_t reg = (int64_t)c->k * p->period_us, wpt = p->tw_us[c->w];
        int64_t t;
        if (reg < wpt) {
            ++c->k;
            if (wpt - reg < min || reg - c->last < min)
                continue;
            t = reg;
        } else {
            if (reg == wpt)
                ++c->k;
            const int w = c->w++;
            if (w < final && (p->tw_us[w + 1] - wpt < min || wpt - c->last < min))
                continue;
            t = wpt;
            if (w == final) {
                c->done = true;
                row->t = (double)(t + PLAN_HOLD_US) * 1e-6;
                plan_path_eval(&p->path, p->path.length, row->pose, NULL, NULL);
                c->last = t;
                return 1;
            }
        }
        c->last = t;
        row->t = (double)(t + PLAN_HOLD_US) * 1e-6;
        plan_pose_at(p, (double)t * 1e-6, row->pose);
        return 1;
    }
    return 0;
}

double plan_duration(const plan *p)
{
    return (double)(p->tw_us[p->n - 1] + PLAN_HOLD_US) * 1e-6;
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
    const int64_t at = llround(t * 1e6) - PLAN_HOLD_US;
    int w = 0;
    while (w + 1 < p->n && p->tw_us[w + 1] <= at)
        ++w;
    return w;
}
