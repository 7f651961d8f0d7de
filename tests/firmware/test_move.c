/* Move planning: validated paths stay within every slide limit when sampled independently, the
 * plate obeys the speed asked for, and a path that leaves the workspace mid-way is caught with
 * its first failing point; one no stretch can slow enough is refused naming its slide. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>

#include "fw/move.h"

static tse_geometry G;
static const fw_limits LIM = {0.2, 1.0, 0.3, 1.0, 10.0, 0.5, 2.0, 1000.0, FW_LIMIT_SLIDE_VMAX};

static int setup(void **state)
{
    (void)state;
    tse_params p;
    tse_params_default(&p);
    return tse_geometry_init(&G, &p) == TSE_PARAM_OK ? 0 : -1;
}

static void solve(const double pose[6], const double *seed, double q[6])
{
    tse_ik_result r;
    assert_int_equal(tse_ik(&G, pose, seed, &r), TSE_OK);
    for (int k = 0; k < 6; ++k)
        q[k] = r.q[k];
}

/* Samples the planned move at its segment grid and measures the slides by finite differences:
 * speed per segment, acceleration as the change of speed over 10 segments (with rest before and
 * after). */
static void measure(const fw_move *mv, const double q0[6], double *vpeak, double *apeak, double *plate_v)
{
    enum { STRIDE = 10 };
    const int n = (int)mv->segments;
    double (*v)[6] = calloc((size_t)n + 2 * STRIDE, sizeof *v);
    double q_prev[6], t_prev = 0.0, p_prev[6];
    for (int k = 0; k < 6; ++k)
        q_prev[k] = q0[k];
    fw_move_pose(mv, 0.0, p_prev);
    *vpeak = *apeak = *plate_v = 0.0;
    for (int s = 1; s <= n; ++s) {
        const double t = fw_move_segment_time(mv, &LIM, (uint32_t)s);
        double pose[6], q[6];
        fw_move_pose(mv, t, pose);
        solve(pose, q_prev, q);
        const double dt = t - t_prev;
        const double dp = sqrt(pow(pose[0] - p_prev[0], 2) + pow(pose[1] - p_prev[1], 2) + pow(pose[2] - p_prev[2], 2));
        if (dt > 0 && dp / dt > *plate_v)
            *plate_v = dp / dt;
        for (int k = 0; k < 6; ++k) {
            v[STRIDE + s - 1][k] = dt > 0 ? (q[k] - q_prev[k]) / dt : 0.0;
            if (fabs(v[STRIDE + s - 1][k]) > *vpeak)
                *vpeak = fabs(v[STRIDE + s - 1][k]);
            q_prev[k] = q[k];
            p_prev[k] = pose[k];
        }
        t_prev = t;
    }
    for (int i = STRIDE; i < n + 2 * STRIDE; ++i)
        for (int k = 0; k < 6; ++k) {
            const double a = fabs(v[i][k] - v[i - STRIDE][k]) * LIM.segment_hz / STRIDE;
            if (a > *apeak)
                *apeak = a;
        }
    free(v);
}

static void test_reachable_move(void **state)
{
    (void)state;
    const double from[6] = {0, 0, 1.0, 0, 0, 0}, to[6] = {0.1, -0.05, 1.3, 0.05, -0.05, 0.2};
    double q0[6];
    solve(from, NULL, q0);
    fw_move mv;
    fw_plan_result res;
    assert_int_equal(fw_move_plan(&mv, &G, &LIM, from, to, FW_MOVE_DURATION, 0.5, q0, &res), 0);
    assert_true(mv.prof.T >= 0.5);
    assert_int_equal(mv.segments, (uint32_t)ceil(mv.prof.T * LIM.segment_hz));
    double end[6];
    fw_move_pose(&mv, mv.prof.T, end);
    for (int k = 0; k < 6; ++k)
        assert_true(end[k] == to[k]);
    double vpeak, apeak, plate_v;
    measure(&mv, q0, &vpeak, &apeak, &plate_v);
    assert_true(vpeak <= LIM.slide_vmax);
    assert_true(apeak <= LIM.slide_amax);
    assert_true(plate_v <= LIM.plate_vmax * (1 + 1e-9));
    /* Asked for 0.5 s, the slides needed more: the move was stretched until a limit binds. */
    assert_true(mv.stretch > 1.0);
    assert_true(vpeak > 0.8 * LIM.slide_vmax || apeak > 0.8 * LIM.slide_amax);
}

static void test_slow_move_keeps_duration(void **state)
{
    (void)state;
    const double from[6] = {0, 0, 1.0, 0, 0, 0}, to[6] = {0.02, 0.01, 1.02, 0, 0, 0.01};
    double q0[6];
    solve(from, NULL, q0);
    fw_move mv;
    fw_plan_result res;
    assert_int_equal(fw_move_plan(&mv, &G, &LIM, from, to, FW_MOVE_DURATION, 3.0, q0, &res), 0);
    assert_true(fabs(mv.prof.T - 3.0) < 1e-9);
    assert_true(mv.stretch == 1.0);
}

static void test_speed_mode(void **state)
{
    (void)state;
    const double from[6] = {0, 0, 0.8, 0, 0, 0}, to[6] = {0.0, 0.0, 1.2, 0, 0, 0};
    double q0[6];
    solve(from, NULL, q0);
    fw_move mv;
    fw_plan_result res;
    assert_int_equal(fw_move_plan(&mv, &G, &LIM, from, to, FW_MOVE_SPEED, 0.05, q0, &res), 0);
    double vpeak, apeak, plate_v;
    measure(&mv, q0, &vpeak, &apeak, &plate_v);
    assert_true(plate_v <= 0.05 * (1 + 1e-9));
    assert_true(plate_v >= 0.05 * 0.99); /* it cruises at the speed asked */
    assert_true(mv.prof.T >= 0.4 / 0.05);
}

/* Both ends reachable; the middle is below the retracted height at the centre (alpha stop). */
static void test_leaves_workspace_midway(void **state)
{
    (void)state;
    const double from[6] = {-0.157, 0.202, 0.312, 0, 0, 0}, to[6] = {0.279, 0.057, 0.312, 0, 0, 0};
    double q0[6], q1[6];
    solve(from, NULL, q0);
    solve(to, NULL, q1);
    fw_move mv;
    fw_plan_result res;
    assert_int_equal(fw_move_plan(&mv, &G, &LIM, from, to, FW_MOVE_DURATION, 2.0, q0, &res), -1);
    assert_int_equal(res.reason, FW_REASON_KINEMATICS);
    assert_true(res.where > 0.0 && res.where < 1.0);
    /* The named point fails, and the path just before it does not. */
    double pose[6];
    for (int k = 0; k < 6; ++k)
        pose[k] = from[k] + res.where * (to[k] - from[k]);
    tse_ik_result r;
    assert_int_not_equal(tse_ik(&G, pose, NULL, &r), TSE_OK);
    assert_int_equal(r.status, res.status);
    assert_int_equal(r.scissor, res.scissor);
    for (int k = 0; k < 6; ++k)
        pose[k] = from[k] + (res.where - 0.01) * (to[k] - from[k]);
    assert_int_equal(tse_ik(&G, pose, NULL, &r), TSE_OK);
}

static void test_unreachable_target_and_bad_input(void **state)
{
    (void)state;
    const double from[6] = {0, 0, 1.0, 0, 0, 0}, to[6] = {0.8, 0, 1.0, 0, 0, 0};
    double q0[6];
    solve(from, NULL, q0);
    fw_move mv;
    fw_plan_result res;
    assert_int_equal(fw_move_plan(&mv, &G, &LIM, from, to, FW_MOVE_DURATION, 1.0, q0, &res), -1);
    assert_int_equal(res.reason, FW_REASON_KINEMATICS);
    assert_true(res.scissor >= 1 && res.scissor <= 3);
    const double nan_to[6] = {0, 0, NAN, 0, 0, 0};
    assert_int_equal(fw_move_plan(&mv, &G, &LIM, from, nan_to, FW_MOVE_DURATION, 1.0, q0, &res), -1);
    assert_int_equal(res.reason, FW_REASON_RANGE);
    assert_int_equal(fw_move_plan(&mv, &G, &LIM, from, from, FW_MOVE_DURATION, 0.0, q0, &res), -1);
}

/* Two moves blended: the path stays within every slide limit when sampled independently, the
 * plate keeps moving through the junction, and it ends on the second target. */
/* Slides that are not where the start pose puts them (B2, q index 3, 0.5 mm off): the first
 * segment must close the gap in 1 ms whatever the duration, so no stretch helps and the move is
 * refused for timing, naming that slide and its speed, 0.5 mm / 1 ms = 0.5 m/s, against the
 * limit parameter 0.2 m/s: 2.5 (the move's own start is still at rest in its first millisecond).
 * With the acceleration limit high enough not to matter. */
static void test_timing_refusal_names_slide(void **state)
{
    (void)state;
    fw_limits lim = LIM;
    lim.slide_amax = 1000.0;
    const double from[6] = {0, 0, 1.0, 0, 0, 0}, to[6] = {0.01, 0, 1.0, 0, 0, 0};
    double q0[6];
    solve(from, NULL, q0);
    q0[3] += 0.0005;
    fw_move mv;
    fw_plan_result res;
    assert_int_equal(fw_move_plan(&mv, &G, &lim, from, to, FW_MOVE_DURATION, 1.0, q0, &res), -1);
    assert_int_equal(res.reason, FW_REASON_TIMING);
    assert_int_equal(res.slide, 4);
    assert_int_equal(res.scissor, 2);
    assert_false(res.accel);
    if (fabs(res.ratio - 2.5) > 0.02)
        fail_msg("ratio %g, by hand 2.5", res.ratio);
}

static void test_blend(void **state)
{
    (void)state;
    const double p0[6] = {0, 0, 1.0, 0, 0, 0}, p1[6] = {0.08, 0, 1.05, 0, 0, 0.05}, p2[6] = {0.08, 0.08, 1.1, 0.03, 0, 0};
    double q0[6];
    solve(p0, NULL, q0);
    static fw_move a, b;
    fw_plan_result res;
    assert_int_equal(fw_move_plan(&a, &G, &LIM, p0, p1, FW_MOVE_DURATION, 3.0, q0, &res), 0);
    assert_int_equal(fw_move_plan(&b, &G, &LIM, p1, p2, FW_MOVE_DURATION, 3.0, a.q_end, &res), 0);
    uint32_t k0;
    assert_int_equal(fw_move_blend(&a, &b, &G, &LIM, 0, &k0), 0);
    assert_true(k0 < a.segments);
    const double t0 = k0 / LIM.segment_hz, T = t0 + b.prof.T;
    const int n = (int)ceil(T * LIM.segment_hz);
    enum { STRIDE = 10 };
    double q[6], prev_pose[6], vpeak = 0, apeak = 0, min_speed = 1e9;
    double (*vel)[6] = calloc((size_t)n + 1, sizeof *vel);
    for (int k = 0; k < 6; ++k)
        q[k] = q0[k];
    fw_move_blend_pose(&a, &b, k0, &LIM, 0.0, prev_pose);
    for (int s = 1; s <= n; ++s) {
        const double t = s == n ? T : s / LIM.segment_hz;
        double pose[6], qn[6];
        fw_move_blend_pose(&a, &b, k0, &LIM, t, pose);
        solve(pose, q, qn);
        const double dt = t - (s - 1) / LIM.segment_hz;
        double speed = 0;
        for (int k = 0; k < 3; ++k)
            speed += (pose[k] - prev_pose[k]) * (pose[k] - prev_pose[k]);
        speed = sqrt(speed) / dt;
        /* Through the junction (a's last ramp), the plate never stops. */
        if (t > a.prof.T - a.prof.Ta && t < a.prof.T + 0.2 * b.prof.Ta)
            min_speed = fmin(min_speed, speed);
        for (int k = 0; k < 6; ++k) {
            vel[s][k] = (qn[k] - q[k]) / dt;
            vpeak = fmax(vpeak, fabs(vel[s][k]));
            if (s >= STRIDE) /* speed change over 10 segments, from rest before the start */
                apeak = fmax(apeak, fabs(vel[s][k] - vel[s - STRIDE][k]) * LIM.segment_hz / STRIDE);
            q[k] = qn[k];
            prev_pose[k] = pose[k];
        }
    }
    free(vel);
    assert_true(vpeak <= LIM.slide_vmax);
    assert_true(apeak <= LIM.slide_amax);
    assert_true(min_speed > 1e-3);
    for (int k = 0; k < 6; ++k)
        assert_true(fabs(prev_pose[k] - p2[k]) < 1e-12);
    /* Moves stretched to the slide limits cannot overlap (their speeds would add): back to back. */
    static fw_move fa, fb;
    assert_int_equal(fw_move_plan(&fa, &G, &LIM, p0, p1, FW_MOVE_DURATION, 0.2, q0, &res), 0);
    assert_int_equal(fw_move_plan(&fb, &G, &LIM, p1, p2, FW_MOVE_DURATION, 0.2, fa.q_end, &res), 0);
    assert_true(fa.stretch > 1.0 && fb.stretch > 1.0);
    assert_int_equal(fw_move_blend(&fa, &fb, &G, &LIM, 0, &k0), 1);
    assert_int_equal(k0, fa.segments);
    /* Too late to blend: back to back. */
    assert_int_equal(fw_move_blend(&a, &b, &G, &LIM, a.segments, &k0), 1);
    assert_int_equal(k0, a.segments);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_reachable_move),
        cmocka_unit_test(test_slow_move_keeps_duration),
        cmocka_unit_test(test_speed_mode),
        cmocka_unit_test(test_leaves_workspace_midway),
        cmocka_unit_test(test_unreachable_target_and_bad_input),
        cmocka_unit_test(test_blend),
        cmocka_unit_test(test_timing_refusal_names_slide),
    };
    return cmocka_run_group_tests(tests, setup, NULL);
}
