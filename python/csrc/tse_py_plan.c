/* tse.plan: the planner (planner/, tse-kin plan's) over the caller's arrays.  See tse_py.h. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "plan_text.h"
#include "tse_py.h"

long tse_py_plan(const int *params, int n_params, unsigned step_hz, unsigned segment_hz, long n, const double *poses,
                 const double *t, const double *v, double period, double blend, double jmax, long cap, double *rows,
                 double stats[8], char *err, size_t errlen)
{
    memset(stats, 0, 8 * sizeof *stats);
    if (n_params != FP_COUNT)
        return -2;
    if (!fw_rates_run((fw_rates){step_hz, segment_hz})) {
        snprintf(err, errlen,
                 "%u Hz step interrupts and %u Hz control segments: no controller runs at these rates (a control "
                 "segment of whole microseconds and whole step interrupts)",
                 step_hz, segment_hz);
        return -1;
    }
    fw_param_set s;
    for (int i = 0; i < FP_COUNT; ++i)
        s.v[i] = params[i];
    if (n < 0 || n > PLAN_WAYPOINTS_MAX) {
        snprintf(err, errlen, "%ld waypoints: at most %d", n, PLAN_WAYPOINTS_MAX);
        return -1;
    }
    plan_waypoint *wp = malloc((size_t)(n ? n : 1) * sizeof *wp);
    if (!wp) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    for (long i = 0; i < n; ++i) {
        memcpy(wp[i].pose, &poses[6 * i], sizeof wp[i].pose);
        wp[i].t = t ? t[i] : NAN;
        wp[i].v = v ? v[i] : NAN;
        wp[i].line = 0;
        wp[i].number = 0; /* messages count from 1 */
    }
    plan_options o;
    plan_options_default(&o);
    o.period = period;
    o.blend = blend;
    o.jmax = jmax < 0.0 ? PLAN_JMAX_CONTROLLER : jmax;
    o.rates = (fw_rates){step_hz, segment_hz};
    plan_made m;
    long rc = -1;
    if (plan_text_make(&s, wp, (int)n, &o, "plan", &m, err, errlen) == 0) {
        rc = plan_row_count(m.p);
        plan_stats st;
        plan_measure(m.p, &st);
        const double figures[8] = {plan_duration(m.p), st.v_peak, st.a_peak, st.v_limit, st.a_limit,
                                   (double)st.rows_mid, (double)st.rows_near, (double)plan_retries(m.p)};
        memcpy(stats, figures, sizeof figures);
        if (rc <= cap) {
            plan_cursor c;
            plan_row row;
            long k = 0;
            for (plan_rows_begin(m.p, &c); plan_rows_next(m.p, &c, &row); ++k) {
                rows[7 * k] = row.t;
                memcpy(&rows[7 * k + 1], row.pose, sizeof row.pose);
            }
        }
    }
    free(m.mem);
    free(wp);
    return rc;
}
