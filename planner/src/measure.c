/* How near a plan's rows come to the slide limits, row by row, as the controller's validator
 * measures them (its worst values taken after each row); and, for a plan with a jerk limit, how
 * near its slides' jerk comes to it, by third differences over four rows evenly apart. */
#include <math.h>
#include <string.h>

#include "plan_internal.h"
#include "tse/ik.h"

/* The slides' jerk over the last four rows, against the limit; 0 when they are not evenly apart. */
static double jerk_ratio(const double q[4][6], const double t[4], double jmax)
{
    const double P = t[1] - t[0];
    for (int m = 1; m < 3; ++m)
        if (fabs((t[m + 1] - t[m]) - P) > 2e-6)
            return 0.0;
    double worst = 0.0;
    for (int k = 0; k < 6; ++k)
        worst = fmax(worst, fabs(q[3][k] - 3.0 * q[2][k] + 3.0 * q[1][k] - q[0][k]) / (P * P * P));
    return worst / jmax;
}

int plan_measure(const plan *p, plan_stats *st)
{
    traj_checker c;
    st->v_peak = st->a_peak = st->j_peak = 0.0;
    st->rows_mid = st->rows_near = 0;
    st->v_limit = (double)p->lim.slide_vmax;
    st->a_limit = (double)(FW_PATH_MARGIN * p->lim.slide_amax); /* what rows may use (fw/path.h) */
    st->j_limit = p->jmax;
    if (traj_checker_start(&c, &p->set, p->opt.rates, p->wp[0].pose, p->q0) != 0)
        return -1;
    /* The motion's time: from the row holding the start to the last. */
    const double t0 = plan_hold(p), T = plan_duration(p) - t0;
    plan_cursor cur;
    plan_row row;
    int64_t prev = 0;
    long k = 0;
    int32_t reject[PROTO_MAX_FIELDS];
    double q[4][6], tq[4];
    for (plan_rows_begin(p, &cur); plan_rows_next(p, &cur, &row); ++k) {
        const int64_t t = (int64_t)(row.t * 1e6 + 0.5);
        if (traj_checker_push(&c, (uint32_t)(t - prev), row.pose, k == p->rows - 1, reject) != 0)
            return -1;
        prev = t;
        double v, a, j = 0.0;
        traj_checker_take_peaks(&c, &v, &a); /* this row's own */
        if (p->jmax > 0.0) {
            tse_ik_result ik;
            if (tse_ik(&p->g, row.pose, k > 0 ? q[3] : p->q0, &ik) != TSE_OK)
                return -1;
            memmove(q, q[1], 3 * sizeof q[0]);
            memmove(tq, tq + 1, 3 * sizeof tq[0]);
            memcpy(q[3], ik.q, sizeof q[3]);
            tq[3] = row.t;
            if (k >= 4) /* (the hold row and the first of the motion are far apart: from the fifth) */
                j = jerk_ratio((const double(*)[6])q, tq, p->jmax);
        }
        st->v_peak = fmax(st->v_peak, v);
        st->a_peak = fmax(st->a_peak, a);
        st->j_peak = fmax(st->j_peak, j);
        if (row.t >= t0 + 0.05 * T && row.t <= t0 + 0.95 * T) {
            ++st->rows_mid;
            if (fmax(fmax(v, a), j) >= 0.9)
                ++st->rows_near;
        }
    }
    return 0;
}
