/* Plans of many paths: every one accepted by the controller's validator (judged here, row by row,
 * not by the planner's word), fast (at 60 % or more of the rows outside the first and last 5 % of
 * the time some slide is at 90 % or more of its speed or acceleration limit), through every
 * waypoint (within 10 um) or cutting corners by at most the blend asked; times kept; and refusals
 * that name the waypoint and the reason. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "fw/limits.h"
#include "fw/types.h"
#include "plan_support.h"
#include "tse/ik.h"

#define PI 3.14159265358979323846

/* The distance from point c to the segment a-b, in position [m]. */
static double to_segment(const double a[3], const double b[3], const double c[3])
{
    double ab[3], ac[3], l2 = 0.0, d = 0.0;
    for (int k = 0; k < 3; ++k) {
        ab[k] = b[k] - a[k];
        ac[k] = c[k] - a[k];
        l2 += ab[k] * ab[k];
        d += ab[k] * ac[k];
    }
    const double u = l2 > 0.0 ? fmin(fmax(d / l2, 0.0), 1.0) : 0.0;
    double e = 0.0;
    for (int k = 0; k < 3; ++k)
        e += pow(a[k] + u * ab[k] - c[k], 2);
    return sqrt(e);
}

/* The least distance from each waypoint to the path the controller runs (straight between rows, from
 * the start at `from`). */
static double farthest_waypoint(const plan *p, const double from[3], const plan_waypoint *wp, int n)
{
    double worst = 0.0;
    for (int w = 0; w < n; ++w) {
        double best = INFINITY, prev[3];
        memcpy(prev, from, sizeof prev);
        plan_cursor c;
        plan_row row;
        for (plan_rows_begin(p, &c); plan_rows_next(p, &c, &row);) {
            best = fmin(best, to_segment(prev, row.pose, wp[w].pose));
            memcpy(prev, row.pose, sizeof prev);
        }
        worst = fmax(worst, best);
    }
    return worst;
}

static unsigned long long rng = 0x9E3779B97F4A7C15ull;
static double uniform(double lo, double hi)
{
    rng = rng * 6364136223846793005ull + 1442695040888963407ull;
    return lo + (hi - lo) * (double)(rng >> 11) / 9007199254740992.0;
}

/* Set number `set`'s waypoints: 3 to 12 of them, a few centimetres and hundredths of a radian
 * apart around the middle of the workspace, yaw within 0.2 rad.  Returns how many. */
static int random_waypoints(int set, plan_waypoint wp[12])
{
    const int n = 3 + set % 10;
    for (int i = 0; i < n; ++i)
        wp[i] = waypoint(uniform(-0.06, 0.06), uniform(-0.06, 0.06), uniform(0.95, 1.15), uniform(-0.04, 0.04),
                         uniform(-0.04, 0.04), uniform(-0.2, 0.2));
    return n;
}

static void test_random_paths(void **state)
{
    (void)state;
    const double periods[] = {0.02, 0.015};
    long mid = 0, near = 0;
    for (int set = 0; set < 24; ++set) {
        plan_waypoint wp[12];
        const int n = random_waypoints(set, wp);
        plan_options o;
        plan_options_default(&o);
        o.period = periods[set % 2];
        o.blend = set % 3 == 2 ? 0.004 : 0.0;
        plan_result r;
        plan *p = make_plan(NULL, wp, n, &o, &r);
        char why[512];
        if (!p)
            fail_msg("set %d: %s", set, plan_explain(&r, wp, why, sizeof why));
        const judged j = judge_rows(NULL, p, wp[0].pose);
        assert_int_equal(j.refused_row, -1);
        assert_true(j.v_peak <= 1.0 && j.a_peak <= 1.0);
        const double share = (double)j.rows_near / (double)j.rows_mid;
        printf("# set %2d: %2d waypoints, %s, rows %.3f s apart: %.3f s, %ld rows; %.0f %% of rows near a limit\n", set,
               n, o.blend > 0 ? "blend 4 mm" : "spline", o.period, plan_duration(p), plan_row_count(p), 100.0 * share);
        assert_true(share >= 0.6);
        if (o.blend == 0.0)
            assert_true(farthest_waypoint(p, wp[0].pose, wp, n) <= 10e-6);
        mid += j.rows_mid;
        near += j.rows_near;
        free_plan(p);
    }
    printf("# all sets: %.1f %% of rows near a limit\n", 100.0 * (double)near / (double)mid);
}

/* Planned for a controller at 100 kHz step interrupts (INFO's rates, not the built-in 200 kHz): its
 * step generator allows 0.9 x (100 - 2) steps per 1 ms segment at 1.28M steps/m, 0.06890625 m/s,
 * half the built-in rates' 0.13921875.  A 20 cm rise reaches that speed: its plan keeps to the lower
 * limit (every row accepted at 100 kHz), takes longer (1.03 s against 0.83 s), and the plan made for
 * 200 kHz is refused there. */
static void test_plans_at_the_controllers_rates(void **state)
{
    (void)state;
    const plan_waypoint wp[2] = {waypoint(0, 0, 0.95, 0, 0, 0), waypoint(0, 0, 1.15, 0, 0, 0)};
    const fw_rates slow = {100000, 1000};
    plan_options o;
    plan_options_default(&o);
    plan_result r;
    plan *fast = make_plan(NULL, wp, 2, &o, &r);
    assert_non_null(fast);
    o.rates = slow;
    plan *p = make_plan(NULL, wp, 2, &o, &r);
    assert_non_null(p);
    plan_stats st_fast, st;
    assert_int_equal(plan_measure(fast, &st_fast), 0);
    assert_int_equal(plan_measure(p, &st), 0);
    assert_true(fabs(st_fast.v_limit - 0.13921875) < 1e-12);
    assert_true(fabs(st.v_limit - 0.06890625) < 1e-12);
    const judged j = judge_rows_at(NULL, slow, p, wp[0].pose);
    assert_int_equal(j.refused_row, -1);
    assert_true(j.v_peak > 0.9 && j.v_peak <= 1.0); /* at the lower limit, within it */
    assert_true(judge_rows_at(NULL, slow, fast, wp[0].pose).refused_row >= 0);
    printf("# a 20 cm rise: %.3f s at 200 kHz steps, %.3f s at 100 kHz\n", plan_duration(fast), plan_duration(p));
    assert_true(plan_duration(p) > plan_duration(fast) + 0.1);
    free_plan(fast);
    free_plan(p);
}

/* A square's corners are cut, by at most the blend asked (the blend's middle is l |d2 - d1| / 4 from
 * the corner: within it, and the controller's rows lie on it within the rounding). */
static void test_blend_cuts_corners(void **state)
{
    (void)state;
    const double a = 0.04;
    const plan_waypoint wp[5] = {waypoint(0, 0, 1.0, 0, 0, 0), waypoint(a, 0, 1.0, 0, 0, 0), waypoint(a, a, 1.0, 0, 0, 0),
                                 waypoint(0, a, 1.0, 0, 0, 0), waypoint(0, 0, 1.0, 0, 0, 0)};
    const double blends[] = {0.001, 0.005};
    double T[2];
    for (int k = 0; k < 2; ++k) {
        plan_options o;
        plan_options_default(&o);
        o.blend = blends[k];
        plan_result r;
        plan *p = make_plan(NULL, wp, 5, &o, &r);
        assert_non_null(p);
        assert_int_equal(judge_rows(NULL, p, wp[0].pose).refused_row, -1);
        for (int w = 1; w < 4; ++w) {
            const double d = farthest_waypoint(p, wp[0].pose, &wp[w], 1);
            assert_true(d <= blends[k] + 2e-6);
            assert_true(d >= 0.5 * blends[k]); /* and it is cut, not stopped at */
        }
        T[k] = plan_duration(p);
        free_plan(p);
    }
    /* A wider blend lets the plate keep more speed through the corners. */
    assert_true(T[1] < T[0]);
}

static void test_times_kept(void **state)
{
    (void)state;
    plan_waypoint wp[4] = {waypoint(0, 0, 1.0, 0, 0, 0), waypoint(0.03, 0, 1.0, 0, 0, 0), waypoint(0.03, 0.03, 1.05, 0, 0, 0),
                           waypoint(0, 0.03, 1.0, 0, 0, 0.1)};
    wp[2].t = 3.0;
    wp[3].t = 4.5;
    plan_result r;
    plan *p = make_plan(NULL, wp, 4, NULL, &r);
    assert_non_null(p);
    assert_int_equal(judge_rows(NULL, p, wp[0].pose).refused_row, -1);
    /* The rows hold one at each waypoint: the row nearest waypoint 3 is at its t, within a millisecond. */
    plan_cursor c;
    plan_row row;
    int hit = 0;
    for (plan_rows_begin(p, &c); plan_rows_next(p, &c, &row);) {
        double d = 0.0;
        for (int k = 0; k < 3; ++k)
            d += pow(row.pose[k] - wp[2].pose[k], 2);
        if (sqrt(d) < 1e-6) {
            assert_true(fabs(row.t - 3.0) <= 1e-3);
            hit = 1;
        }
    }
    assert_true(hit);
    assert_true(fabs(plan_duration(p) - 4.5) <= 1e-3);
    free_plan(p);
    /* Too soon for the slides: refused, naming the waypoint and the earliest time. */
    wp[2].t = 0.1;
    assert_null(make_plan(NULL, wp, 4, NULL, &r));
    assert_int_equal(r.status, PLAN_TIME);
    assert_int_equal(r.waypoint, 2);
    assert_true(r.t_needed > 0.1);
}

/* A plan the validator refuses is not returned: planned without margins (at the very limits, where
 * the rows' rounding takes some slide over) and with no retry allowed, the figure eight is refused
 * with the row and the controller's REJECT (a timing one). */
static void test_never_returns_refused(void **state)
{
    (void)state;
    plan_waypoint wp[17];
    for (int k = 0; k < 17; ++k)
        wp[k] = waypoint(0.05 * sin(2 * PI * k / 16), 0.05 * sin(4 * PI * k / 16), 1.0, 0, 0, 0);
    plan_options o;
    plan_options_default(&o);
    o.v_margin = o.a_margin = 1.0;
    o.retries = 0;
    plan_result r;
    assert_null(make_plan(NULL, wp, 17, &o, &r));
    assert_int_equal(r.status, PLAN_REFUSED);
    assert_true(r.row >= 0);
    assert_int_equal(r.reject[2], FW_REASON_TIMING);
    /* With its margins and retries the same path is planned, and the rows pass. */
    plan *p = make_plan(NULL, wp, 17, NULL, &r);
    assert_non_null(p);
    assert_int_equal(judge_rows(NULL, p, wp[0].pose).refused_row, -1);
    free_plan(p);
}

/* The controller stops a trajectory whose queue holds less path than a stop needs: a ramp shedding
 * the fastest slide speed v within 45 % of slide_amax lasts 2 v / (0.45 amax), and it wants half of
 * it queued (docs/controller.md).  A host keeps at most its 32 rows less the 4 in flight queued, so
 * over every 28 rows the path must last v / (0.45 amax) at the speeds of those rows, whatever the
 * waypoints' spacing; rows closer than the speed limit allows are refused as a period. */
static void test_rows_keep_the_controllers_queue_deep(void **state)
{
    (void)state;
    enum { N = 240, QUEUED = 28 };
    static plan_waypoint wp[N + 1];
    for (int k = 0; k <= N; ++k) /* a circle of 240 waypoints 1.3 mm apart */
        wp[k] = waypoint(0.05 * cos(2 * PI * k / N) - 0.05, 0.05 * sin(2 * PI * k / N), 1.0, 0, 0, 0);
    plan_result r;
    plan *p = make_plan(NULL, wp, N + 1, NULL, &r);
    assert_non_null(p);
    fw_param_set s;
    fw_params_default(&s);
    const double amax = s.v[FP_SLIDE_AMAX] * 1e-6;
    tse_params kp;
    tse_params_default(&kp);
    tse_geometry g;
    assert_int_equal(tse_geometry_init(&g, &kp), TSE_PARAM_OK);
    static double t[4096], v[4096];
    double q_prev[6];
    tse_ik_result ik;
    assert_int_equal(tse_ik(&g, wp[0].pose, NULL, &ik), TSE_OK);
    memcpy(q_prev, ik.q, sizeof q_prev);
    plan_cursor c;
    plan_row row;
    int n = 0;
    for (plan_rows_begin(p, &c); plan_rows_next(p, &c, &row) && n < 4096; ++n) {
        assert_int_equal(tse_ik(&g, row.pose, q_prev, &ik), TSE_OK);
        t[n] = row.t;
        v[n] = 0.0;
        for (int k = 0; k < 6; ++k)
            v[n] = fmax(v[n], fabs(ik.q[k] - q_prev[k]) / (row.t - (n ? t[n - 1] : 0.0)));
        memcpy(q_prev, ik.q, sizeof q_prev);
    }
    assert_true(fabs(t[0] - s.v[FP_TRAJ_LEAD] * 1e-6) < 1e-9); /* the hold: the controller's lead */
    for (int i = 1; i + QUEUED < n; ++i) {
        double peak = 0.0;
        for (int j = i; j <= i + QUEUED; ++j)
            peak = fmax(peak, v[j]);
        if (!(t[i + QUEUED] - t[i] >= peak / (0.45 * amax)))
            fail_msg("rows %d..%d: %.4f s of path queued, a stop from %.4f m/s needs %.4f s", i, i + QUEUED,
                     t[i + QUEUED] - t[i], peak, peak / (0.45 * amax));
    }
    free_plan(p);
    /* Rows 10 ms apart: too close at the defaults' speed limit, refused naming the least period. */
    plan_options o;
    plan_options_default(&o);
    o.period = 0.01;
    assert_null(make_plan(NULL, wp, N + 1, &o, &r));
    assert_int_equal(r.status, PLAN_BAD_INPUT);
    assert_true(r.period_min > 0.01 && r.period_min < 0.02);
    char why[512];
    assert_non_null(strstr(plan_explain(&r, wp, why, sizeof why), "use --period"));
}

static void check_refusal(const plan_waypoint *wp, int n, plan_status status, int waypoint, int between,
                          const char *words)
{
    plan_result r;
    assert_null(make_plan(NULL, wp, n, NULL, &r));
    char why[512];
    plan_explain(&r, wp, why, sizeof why);
    printf("# refused: %s\n", why);
    assert_int_equal(r.status, status);
    assert_int_equal(r.waypoint, waypoint);
    if (status == PLAN_WORKSPACE)
        assert_int_equal(r.between, between);
    assert_non_null(strstr(why, words));
}

static void test_refusals_name_the_waypoint(void **state)
{
    (void)state;
    /* Above the angle stops at the centre (L sin(alpha_max) = 1.62 m). */
    plan_waypoint high[3] = {waypoint(0, 0, 1.0, 0, 0, 0), waypoint(0, 0, 1.2, 0, 0, 0), waypoint(0, 0, 1.7, 0, 0, 0)};
    high[2].line = 9;
    check_refusal(high, 3, PLAN_WORKSPACE, 2, 0, "waypoint 3 (line 9)");
    /* Both ends reachable at z = 0.32 m, x = +-0.15 m, the middle of the way is not: off the axis, low
     * scissors reach their lower angle stop (tse-kin ik: (0.1, 0, 0.32) is 'alpha'). */
    const plan_waypoint low[2] = {waypoint(0.15, 0, 0.32, 0, 0, 0), waypoint(0, 0, 0.32, 0, 0, 0)};
    check_refusal(low, 2, PLAN_WORKSPACE, 0, 1, "angle stop");
    /* A waypoint that repeats the one before. */
    const plan_waypoint twice[3] = {waypoint(0, 0, 1.0, 0, 0, 0), waypoint(0, 0, 1.1, 0, 0, 0), waypoint(0, 0, 1.1, 0, 0, 0)};
    check_refusal(twice, 3, PLAN_BAD_INPUT, 2, 0, "waypoint 3");
    /* One waypoint is no path. */
    const plan_waypoint one[1] = {waypoint(0, 0, 1.0, 0, 0, 0)};
    check_refusal(one, 1, PLAN_BAD_INPUT, -1, 0, "at least 2");
}

/* The same random waypoint sets planned with the controller's slide jerk limit J (PLAN_JMAX_CONTROLLER):
 * every plan accepted by the validator, through its waypoints; each slide's jerk, from the rows'
 * slides by differences (rows evenly 5 ms apart within a stretch: four in a row of one spacing),
 * within J but for the rows' own rounding; and fast: at 60 % or more of the rows outside the first
 * and last 5 % of the time some slide is at 90 % or more of its speed, acceleration or jerk limit
 * (speed and acceleration by first and second differences over the rows, the acceleration as the
 * validator measures it, over 10 ms). */
static void test_random_paths_jerk_limited(void **state)
{
    (void)state;
    fw_param_set s;
    fw_params_default(&s);
    s.v[FP_SLIDE_AMAX] = 4000000; /* rows 5 ms apart need a deeper queue's worth of stop (plan.h) */
    /* slide_amax x plate_jmax / plate_amax; the rows' share of slide_amax. */
    const double J = 4.0 * (double)s.v[FP_PLATE_JMAX] / (double)s.v[FP_PLATE_AMAX], a_rows = 0.95 * 4.0;
    assert_true(J > 0.0);
    fw_speed_limit sl;
    assert_int_equal(fw_speed_limit_from_params(&s, FW_STEP_HZ, FW_SEGMENT_HZ, &sl), 0);
    const double v_lim = (double)sl.vmax;
    tse_params kp;
    tse_params_default(&kp);
    tse_geometry g;
    assert_int_equal(tse_geometry_init(&g, &kp), TSE_PARAM_OK);
    double worst_all = 0.0;
    for (int set = 0; set < 12; ++set) {
        plan_waypoint wp[12];
        const int n = random_waypoints(set, wp);
        plan_options o;
        plan_options_default(&o);
        o.period = 0.005;
        plan_result r;
        plan *p0 = make_plan(&s, wp, n, &o, &r);
        assert_non_null(p0);
        o.jmax = PLAN_JMAX_CONTROLLER; /* J */
        plan *p = make_plan(&s, wp, n, &o, &r);
        char why[512];
        if (!p)
            fail_msg("set %d: %s", set, plan_explain(&r, wp, why, sizeof why));
        assert_int_equal(judge_rows(&s, p, wp[0].pose).refused_row, -1);
        assert_true(farthest_waypoint(p, wp[0].pose, wp, n) <= 10e-6);
        double q[5][6], t[5], worst = 0.0, seed[6];
        int have = 0;
        long mid = 0, near = 0;
        const double t0 = plan_hold(p), T_all = plan_duration(p) - t0;
        plan_cursor c;
        plan_row row;
        for (plan_rows_begin(p, &c); plan_rows_next(p, &c, &row);) {
            tse_ik_result ik;
            assert_int_equal(tse_ik(&g, row.pose, have ? seed : NULL, &ik), TSE_OK);
            memcpy(seed, ik.q, sizeof seed);
            memmove(q, q[1], 4 * sizeof q[0]);
            memmove(t, t + 1, 4 * sizeof t[0]);
            memcpy(q[4], ik.q, sizeof q[4]);
            t[4] = row.t;
            if (++have < 6)
                continue;
            bool even = true;
            for (int m = 1; m < 4; ++m)
                even = even && fabs((t[m + 1] - t[m]) - (t[1] - t[0])) < 2e-6;
            const double P = t[1] - t[0];
            double fv = 0.0, fa = 0.0, fj = 0.0;
            for (int k = 0; k < 6; ++k) {
                fv = fmax(fv, fabs(q[4][k] - q[3][k]) / (t[4] - t[3]) / v_lim);
                if (even) {
                    fa = fmax(fa, fabs(q[4][k] - 2.0 * q[2][k] + q[0][k]) / (4.0 * P * P) / a_rows);
                    const double j = fabs(q[4][k] - 3.0 * q[3][k] + 3.0 * q[2][k] - q[1][k]) / (P * P * P);
                    worst = fmax(worst, j);
                    fj = fmax(fj, j / J);
                }
            }
            if (t[2] - t0 > 0.05 * T_all && t[2] - t0 < 0.95 * T_all) {
                ++mid;
                near += fv >= 0.9 || fa >= 0.9 || fj >= 0.9;
            }
        }
        const double longer = plan_duration(p) - plan_duration(p0), A = a_rows * o.a_margin;
        printf("# set %2d, jerk-limited: %.3f s (%.3f s longer than without, A / J %.3f s), retries %d; slide jerk "
               "at most %.1f of %.1f m/s^3; %.0f %% of rows near a limit\n",
               set, plan_duration(p), longer, A / J, plan_retries(p), worst, J, 100.0 * (double)near / (double)mid);
        /* The rows are in whole micrometres: over 5 ms their third differences may be off by
         * 8 um / (5 ms)^3 = 64 m/s^3 at worst, a fraction of it on average: the bound is J plus that
         * share of it the jerk of a row of one micrometre rounding makes here. */
        assert_true(worst <= 1.10 * J + 8e-6 / (0.005 * 0.005 * 0.005) * 0.25);
        assert_true(longer >= A / J - 0.002);
        assert_true(near >= 0.6 * (double)mid);
        worst_all = fmax(worst_all, worst);
        free_plan(p);
        free_plan(p0);
    }
    printf("# all jerk-limited sets: slide jerk at most %.1f of %.1f m/s^3\n", worst_all, J);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_random_paths),
        cmocka_unit_test(test_random_paths_jerk_limited),
        cmocka_unit_test(test_blend_cuts_corners),
        cmocka_unit_test(test_times_kept),
        cmocka_unit_test(test_never_returns_refused),
        cmocka_unit_test(test_rows_keep_the_controllers_queue_deep),
        cmocka_unit_test(test_refusals_name_the_waypoint),
        cmocka_unit_test(test_plans_at_the_controllers_rates),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
