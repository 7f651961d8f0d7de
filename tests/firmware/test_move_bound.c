/* What set a planned move's pace (fw_move.bound, sent as MOVE_INFO), against the profile's limits
 * worked out by hand.  With slide limits far out of reach, the plate limits on the path parameter
 * u are the plate limits over the move's length (or angle), and the fastest rest-to-rest profile
 * (fw/profile.h) is:
 * - a cruise at V when D >= V Ta(V), Ta(V) = max(2V/A, sqrt(2 pi V/J)): the speed limit binds;
 * - otherwise ramps meeting at the smaller of sqrt(A D/2) (acceleration) and cbrt(D^2 J/(2 pi))
 *   (jerk), which names the limit.
 * LIM_PLATE's plate limits: 0.3 m/s, 1 m/s^2, 10 m/s^3, 0.5 rad/s, 2 rad/s^2 (so the rotation's
 * jerk limit is 2 x 10 / 1 = 20 rad/s^3).  A request the limits can meet is what binds; slide
 * limits that stretch a move name the slide and its demand, checked against the demand measured
 * independently on the unstretched profile. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "fw/move.h"

static tse_geometry G;
/* slide_vmax, slide_amax, plate_vmax, amax, jmax, wmax, dwmax, segment_hz */
static const fw_limits LIM_PLATE = {100.0, 1000.0, 0.3, 1.0, 10.0, 0.5, 2.0, 1000.0};

static int setup(void **state)
{
    (void)state;
    tse_params p;
    tse_params_default(&p);
    return tse_geometry_init(&G, &p) == TSE_PARAM_OK ? 0 : -1;
}

static fw_move plan(const fw_limits *lim, const double to[6], fw_move_kind kind, double value)
{
    const double from[6] = {0, 0, 1.0, 0, 0, 0};
    tse_ik_result r;
    assert_int_equal(tse_ik(&G, from, NULL, &r), TSE_OK);
    fw_move mv;
    fw_plan_result res;
    assert_int_equal(fw_move_plan(&mv, &G, lim, from, to, kind, value, r.q, &res), 0);
    return mv;
}

static void plate_limits(void **state)
{
    (void)state;
    const struct {
        double to[6];
        uint8_t bound;
        const char *why;
    } cases[] = {
        /* 0.3 m up: V Ta = 0.3 x max(0.6, 0.434) = 0.18 m <= 0.3: a cruise. */
        {{0, 0, 1.3, 0, 0, 0}, FW_BOUND_PLATE_VMAX, "0.3 m cruises at plate_vmax"},
        /* 0.15 m: no cruise; sqrt(1 x 0.15 / 2) = 0.274 < cbrt(0.0225 x 10 / 2 pi) = 0.330. */
        {{0, 0, 1.15, 0, 0, 0}, FW_BOUND_PLATE_AMAX, "0.15 m: the acceleration limit"},
        /* 0.01 m: sqrt(0.005) = 0.0707 > cbrt(1e-4 x 10 / 2 pi) = 0.0542. */
        {{0.01, 0, 1.0, 0, 0, 0}, FW_BOUND_PLATE_JMAX, "1 cm: the jerk limit"},
        /* Yaw 1 rad: V Ta = 0.5 x max(0.5, 0.396) = 0.25 rad <= 1. */
        {{0, 0, 1.0, 0, 0, 1.0}, FW_BOUND_PLATE_WMAX, "1 rad cruises at plate_wmax"},
        /* Yaw 0.2 rad: sqrt(2 x 0.2 / 2) = 0.447 < cbrt(0.04 x 20 / 2 pi) = 0.503. */
        {{0, 0, 1.0, 0, 0, 0.2}, FW_BOUND_PLATE_DWMAX, "0.2 rad: the angular acceleration limit"},
        /* Yaw 0.01 rad: sqrt(0.01) = 0.1 > cbrt(1e-4 x 20 / 2 pi) = 0.0683. */
        {{0, 0, 1.0, 0, 0, 0.01}, FW_BOUND_PLATE_JMAX_ANGULAR, "0.01 rad: the angular jerk limit"},
        /* 0.3 m and 1 rad: per unit of u, speed min(0.3/0.3, 0.5/1) = 0.5 from the rotation,
         * acceleration min(1/0.3, 2/1) = 2, jerk min(10/0.3, 20/1) = 20: the 1 rad case. */
        {{0, 0, 1.3, 0, 0, 1.0}, FW_BOUND_PLATE_WMAX, "0.3 m with 1 rad: the rotation's speed"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        const fw_move mv = plan(&LIM_PLATE, cases[i].to, FW_MOVE_DURATION, 0.001);
        if (mv.bound != cases[i].bound)
            fail_msg("%s: bound %u, expected %u", cases[i].why, mv.bound, cases[i].bound);
        assert_int_equal(mv.bound_slide, 0);
        assert_true(mv.bound_ratio == 0.0);
        assert_true(mv.stretch == 1.0);
    }
}

static void request_binds(void **state)
{
    (void)state;
    const double up[6] = {0, 0, 1.3, 0, 0, 0};
    /* The fastest is 0.3 / 0.3 + 0.6 = 1.6 s: 10 s is the request's own pace. */
    fw_move mv = plan(&LIM_PLATE, up, FW_MOVE_DURATION, 10.0);
    assert_int_equal(mv.bound, FW_BOUND_ASKED);
    assert_true(fabs(mv.prof.T - 10.0) < 1e-9);
    /* 1.5 s is shorter than the limits allow: they bind, and the plan lasts 1.6 s. */
    mv = plan(&LIM_PLATE, up, FW_MOVE_DURATION, 1.5);
    assert_int_equal(mv.bound, FW_BOUND_PLATE_VMAX);
    assert_true(fabs(mv.prof.T - 1.6) < 1e-9);
    /* A speed below plate_vmax cruises at it: 0.1 m/s over 0.3 m, with ramps of
     * max(2 x 0.1 / 1, sqrt(2 pi 0.1 / 10)) = 0.2507 s (the jerk's). */
    mv = plan(&LIM_PLATE, up, FW_MOVE_SPEED, 0.1);
    assert_int_equal(mv.bound, FW_BOUND_ASKED);
    assert_true(fabs(mv.prof.T - (0.3 / 0.1 + sqrt(2.0 * 3.14159265358979323846 * 0.1 / 10.0))) < 1e-9);
    /* A speed above it: plate_vmax binds. */
    mv = plan(&LIM_PLATE, up, FW_MOVE_SPEED, 0.5);
    assert_int_equal(mv.bound, FW_BOUND_PLATE_VMAX);
}

/* The slides' peak speed and acceleration along a planned move, sampled on its segment grid with
 * the inverse kinematics and finite differences (speed per segment, acceleration as the change
 * of speed over 10 segments, rest before and after), per slide. */
static void measure(const fw_move *mv, const fw_limits *lim, double v[6], double a[6])
{
    enum { STRIDE = 10, MAXSEG = 20000 };
    static double sv[MAXSEG + 2 * STRIDE][6];
    const int n = (int)mv->segments;
    assert_true(n <= MAXSEG);
    double q_prev[6], t_prev = 0.0;
    for (int k = 0; k < 6; ++k) {
        q_prev[k] = mv->q_from[k];
        v[k] = a[k] = 0.0;
    }
    for (int i = 0; i < n + 2 * STRIDE; ++i)
        for (int k = 0; k < 6; ++k)
            sv[i][k] = 0.0;
    for (int s = 1; s <= n; ++s) {
        const double t = fw_move_segment_time(mv, lim, (uint32_t)s);
        double pose[6];
        fw_move_pose(mv, t, pose);
        tse_ik_result r;
        assert_int_equal(tse_ik(&G, pose, q_prev, &r), TSE_OK);
        for (int k = 0; k < 6; ++k) {
            sv[STRIDE + s - 1][k] = (r.q[k] - q_prev[k]) / (t - t_prev);
            v[k] = fmax(v[k], fabs(sv[STRIDE + s - 1][k]));
            q_prev[k] = r.q[k];
        }
        t_prev = t;
    }
    for (int i = STRIDE; i < n + 2 * STRIDE; ++i)
        for (int k = 0; k < 6; ++k)
            a[k] = fmax(a[k], fabs(sv[i][k] - sv[i - STRIDE][k]) * lim->segment_hz / STRIDE);
}

static void slide_limits_stretch(void **state)
{
    (void)state;
    /* Slide limits a tenth of the usual ones: a 3 s move of 0.2 m up with a turn must stretch. */
    fw_limits slow = LIM_PLATE;
    slow.slide_vmax = 0.02;
    slow.slide_amax = 0.1;
    const double to[6] = {0.05, -0.03, 1.2, 0.05, 0.0, 0.3};
    const fw_move mv = plan(&slow, to, FW_MOVE_DURATION, 3.0);
    assert_true(mv.stretch > 1.0);
    assert_true(mv.bound == FW_BOUND_SLIDE_VMAX || mv.bound == FW_BOUND_SLIDE_AMAX);
    assert_in_range(mv.bound_slide, 1, 6);
    /* The same move unstretched: planned where the slides do not bind. */
    const fw_move fast = plan(&LIM_PLATE, to, FW_MOVE_DURATION, 3.0);
    assert_true(fabs(fast.prof.T - 3.0) < 1e-9);
    double v[6], a[6];
    measure(&fast, &slow, v, a);
    int worst = 0;
    double wr = 0.0;
    for (int k = 0; k < 6; ++k) {
        const double r = mv.bound == FW_BOUND_SLIDE_VMAX ? v[k] / slow.slide_vmax : a[k] / slow.slide_amax;
        if (r > wr) {
            wr = r;
            worst = k + 1;
        }
    }
    /* The planner proves bounds over whole pieces (fw/validate.h): its demand is never below the
     * sampled one, and a bound, not a wild guess. */
    if (!(mv.bound_ratio >= wr * (1.0 - 1e-6) && mv.bound_ratio <= wr * 1.3))
        fail_msg("demand %.4f against %.4f measured", mv.bound_ratio, wr);
    /* Named for the slide that measured worst, unless another is within the bound's slack. */
    const double named = mv.bound == FW_BOUND_SLIDE_VMAX ? v[mv.bound_slide - 1] / slow.slide_vmax
                                                         : a[mv.bound_slide - 1] / slow.slide_amax;
    assert_true(mv.bound_slide == worst || named >= wr / 1.3);
    /* Which of speed and acceleration: the one that needs the longer stretch (speed k, acceleration
     * sqrt(k)), where the two are clearly apart. */
    double vr = 0.0, ar = 0.0;
    for (int k = 0; k < 6; ++k) {
        vr = fmax(vr, v[k] / slow.slide_vmax);
        ar = fmax(ar, a[k] / slow.slide_amax);
    }
    if (vr > 1.3 * sqrt(ar))
        assert_int_equal(mv.bound, FW_BOUND_SLIDE_VMAX);
    if (sqrt(ar) > 1.3 * vr)
        assert_int_equal(mv.bound, FW_BOUND_SLIDE_AMAX);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(plate_limits),
        cmocka_unit_test(request_binds),
        cmocka_unit_test(slide_limits_stretch),
    };
    return cmocka_run_group_tests(tests, setup, NULL);
}
