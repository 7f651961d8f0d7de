#include "plan_support.h"

#include <math.h>
#include <stdlib.h>

#include "fw/limits.h"
#include "traj_checker.h"
#include "tse/ik.h"

static void *mem_of[64];
static const plan *plan_of[64];

plan *make_plan(const fw_param_set *set, const plan_waypoint *wp, int n, const plan_options *o, plan_result *r)
{
    fw_param_set d;
    plan_options od;
    if (!set) {
        fw_params_default(&d);
        set = &d;
    }
    if (!o) {
        plan_options_default(&od);
        o = &od;
    }
    const size_t bytes = plan_bytes(set, wp, n, o);
    void *mem = bytes ? malloc(bytes) : NULL;
    plan *p = plan_make(mem, bytes, set, wp, n, o, r);
    if (!p) {
        free(mem);
        return NULL;
    }
    for (int i = 0; i < 64; ++i)
        if (!plan_of[i]) {
            plan_of[i] = p;
            mem_of[i] = mem;
            return p;
        }
    abort();
}

void free_plan(plan *p)
{
    for (int i = 0; i < 64; ++i)
        if (plan_of[i] == p) {
            free(mem_of[i]);
            plan_of[i] = NULL;
            return;
        }
}

plan_waypoint waypoint(double x, double y, double z, double roll, double pitch, double yaw)
{
    plan_waypoint w = {{x, y, z, roll, pitch, yaw}, NAN, NAN, 0, 0};
    return w;
}

judged judge_rows(const fw_param_set *set, const plan *p, const double pose0[6])
{
    return judge_rows_at(set, FW_RATES_BUILT_IN, p, pose0);
}

judged judge_rows_at(const fw_param_set *set, fw_rates rates, const plan *p, const double pose0[6])
{
    fw_param_set d;
    if (!set) {
        fw_params_default(&d);
        set = &d;
    }
    static traj_checker c;
    judged j = {-1, 0, 0, 0.0, 0.0};
    tse_geometry g;
    fw_limits lim;
    tse_ik_result ik;
    if (fw_limits_from_params(set, rates.step_hz, rates.segment_hz, &g, &lim) != 0 ||
        tse_ik(&g, pose0, NULL, &ik) != TSE_OK || traj_checker_start(&c, set, rates, pose0, ik.q) != 0) {
        j.refused_row = 0;
        return j;
    }
    const double t0 = plan_hold(p), T = plan_duration(p) - t0; /* the motion's time, after the hold */
    const long n = plan_row_count(p);
    plan_cursor cur;
    plan_row row;
    long long prev = 0;
    int32_t reject[PROTO_MAX_FIELDS];
    long k = 0;
    for (plan_rows_begin(p, &cur); plan_rows_next(p, &cur, &row); ++k) {
        const long long t = llround(row.t * 1e6);
        if (traj_checker_push(&c, (uint32_t)(t - prev), row.pose, k == n - 1, reject) != 0) {
            j.refused_row = (int)k;
            return j;
        }
        prev = t;
        double v, a;
        traj_checker_take_peaks(&c, &v, &a); /* this row's own worst demand */
        j.v_peak = fmax(j.v_peak, v);
        j.a_peak = fmax(j.a_peak, a);
        if (row.t >= t0 + 0.05 * T && row.t <= t0 + 0.95 * T) {
            ++j.rows_mid;
            j.rows_near += fmax(v, a) >= 0.9;
        }
    }
    return j;
}
