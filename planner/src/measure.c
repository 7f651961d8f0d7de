/* How near a plan's rows come to the slide limits, row by row, as the controller's validator
 * measures them (its worst values taken after each row). */
#include <math.h>

#include "plan_internal.h"

int plan_measure(const plan *p, plan_stats *st)
{
    traj_checker c;
    st->v_peak = st->a_peak = 0.0;
    st->rows_mid = st->rows_near = 0;
    st->v_limit = (double)p->lim.slide_vmax;
    st->a_limit = (double)(FW_PATH_MARGIN * p->lim.slide_amax); /* what rows may use (fw/path.h) */
    if (traj_checker_start(&c, &p->set, p->wp[0].pose, p->q0) != 0)
        return -1;
    /* The motion's time: from the row holding the start to the last. */
    const double t0 = plan_hold(p), T = plan_duration(p) - t0;
    plan_cursor cur;
    plan_row row;
    int64_t prev = 0;
    long k = 0;
    int32_t reject[PROTO_MAX_FIELDS];
    for (plan_rows_begin(p, &cur); plan_rows_next(p, &cur, &row); ++k) {
        const int64_t t = (int64_t)(row.t * 1e6 + 0.5);
        if (traj_checker_push(&c, (uint32_t)(t - prev), row.pose, k == p->rows - 1, reject) != 0)
            return -1;
        prev = t;
        double v, a;
        traj_checker_take_peaks(&c, &v, &a); /* this row's own */
        st->v_peak = fmax(st->v_peak, v);
        st->a_peak = fmax(st->a_peak, a);
        if (row.t >= t0 + 0.05 * T && row.t <= t0 + 0.95 * T) {
            ++st->rows_mid;
            if (fmax(v, a) >= 0.9)
                ++st->rows_near;
        }
    }
    return 0;
}
