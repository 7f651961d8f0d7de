/* Timed trajectory points: validation on arrival, flow control, atomic refusal, what a timing
 * refusal names, and dropping. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>

#include "fw/traj.h"

static tse_geometry G;
static const fw_limits LIM = {0.2, 1.0, 0.3, 1.0, 10.0, 0.5, 2.0, 1000.0, FW_LIMIT_SLIDE_VMAX};

static int setup(void **state)
{
    (void)state;
    tse_params p;
    tse_params_default(&p);
    return tse_geometry_init(&G, &p) == TSE_PARAM_OK ? 0 : -1;
}

static void start(fw_traj *t, const double pose[6])
{
    tse_ik_result r;
    assert_int_equal(tse_ik(&G, pose, NULL, &r), TSE_OK);
    fw_traj_start(t, &LIM, pose, r.q);
}

/* A smooth 0.1 m rise (minimum-jerk in Z) over 0.6 s, sampled every 20 ms, is accepted point by point and the
 * interpolation passes through every point. */
static void test_smooth_accepted(void **state)
{
    (void)state;
    static fw_traj t;
    const double p0[6] = {0, 0, 1.0, 0, 0, 0};
    start(&t, p0);
    const int n = 30;
    fw_plan_result res;
    for (int i = 1; i <= n; ++i) {
        const double s = (double)i / n, z = 1.0 + 0.1 * (10 * pow(s, 3) - 15 * pow(s, 4) + 6 * pow(s, 5));
        const double p[6] = {0, 0, z, 0, 0, 0};
        if (i <= (int)FW_TRAJ_CAPACITY)
            assert_int_equal(fw_traj_push(&t, &G, &LIM, p, 20000, i == n, &res), 0);
    }
    assert_int_equal(fw_traj_depth(&t), n);
    assert_int_equal(fw_traj_free(&t), FW_TRAJ_CAPACITY - n);
    double pose[6];
    assert_true(fw_traj_pose(&t, 20000 * 15, pose));
    const double s = 0.5, z = 1.0 + 0.1 * (10 * pow(s, 3) - 15 * pow(s, 4) + 6 * pow(s, 5));
    assert_true(fabs(pose[2] - z) < 1e-12);
    assert_int_equal(fw_traj_depth(&t), n - 15); /* the points passed left the queue */
    assert_true(fw_traj_pose(&t, 20000u * n, pose));
    assert_true(fabs(pose[2] - 1.1) < 1e-12);
    assert_false(fw_traj_pose(&t, 20000u * n + 1000u, pose)); /* past the end */
    /* Nothing after the last point. */
    const double p[6] = {0, 0, 1.1, 0, 0, 0};
    assert_int_equal(fw_traj_push(&t, &G, &LIM, p, 20000, false, &res), -1);
    assert_int_equal(res.reason, FW_REASON_STATE);
}

/* A jump the slides cannot make in the time given is refused, and leaves the queue as it was. */
static void test_too_fast_refused_atomically(void **state)
{
    (void)state;
    static fw_traj t;
    const double p0[6] = {0, 0, 1.0, 0, 0, 0};
    start(&t, p0);
    fw_plan_result res;
    const double ok[6] = {0, 0, 1.0005, 0, 0, 0};
    assert_int_equal(fw_traj_push(&t, &G, &LIM, ok, 50000, false, &res), 0);
    const fw_traj before = t;
    const double jump[6] = {0.1, 0, 1.0, 0, 0, 0};
    assert_int_equal(fw_traj_push(&t, &G, &LIM, jump, 10000, false, &res), -1);
    assert_int_equal(res.reason, FW_REASON_TIMING);
    assert_memory_equal(&t, &before, sizeof t);
    const double away[6] = {0.8, 0, 1.0, 0, 0, 0};
    assert_int_equal(fw_traj_push(&t, &G, &LIM, away, 20000000, false, &res), -1);
    assert_int_equal(res.reason, FW_REASON_KINEMATICS);
    assert_memory_equal(&t, &before, sizeof t);
}

/* The slide that moves most between two poses, from the inverse kinematics of each (its travel
 * in *dq); the test needs it clearly ahead of the others, so that the expected slide is not a
 * matter of rounding. */
static int fastest_slide(const double a[6], const double b[6], double *dq)
{
    tse_ik_result ra, rb;
    assert_int_equal(tse_ik(&G, a, NULL, &ra), TSE_OK);
    assert_int_equal(tse_ik(&G, b, ra.q, &rb), TSE_OK);
    int best = 0;
    for (int k = 1; k < 6; ++k)
        if (fabs(rb.q[k] - ra.q[k]) > fabs(rb.q[best] - ra.q[best]))
            best = k;
    for (int k = 0; k < 6; ++k)
        if (k != best)
            assert_true(fabs(rb.q[k] - ra.q[k]) < 0.8 * fabs(rb.q[best] - ra.q[best]));
    *dq = fabs(rb.q[best] - ra.q[best]);
    return best;
}

/* A point too fast for the slide speed limit is refused naming the slide and the ratio of its
 * speed to the limit.  A move along Y and Z together drives B1 (q index 1) clearly fastest; with
 * an acceleration limit too high to matter, the ratio is that slide's travel over dt against
 * vmax (2 % for the curvature of the path in slide space). */
static void test_timing_names_speed(void **state)
{
    (void)state;
    static fw_traj t;
    fw_limits lim = LIM;
    lim.slide_amax = 1000.0;
    const double p0[6] = {0, 0, 1.0, 0, 0, 0}, p1[6] = {0, 0.01, 1.01, 0, 0, 0};
    tse_ik_result r;
    assert_int_equal(tse_ik(&G, p0, NULL, &r), TSE_OK);
    fw_traj_start(&t, &lim, p0, r.q);
    double dq;
    const int k = fastest_slide(p0, p1, &dq);
    const double want = dq / 0.05 / lim.slide_vmax;
    assert_true(want > 1.2);
    fw_plan_result res;
    assert_int_equal(fw_traj_push(&t, &G, &lim, p1, 50000, false, &res), -1);
    assert_int_equal(res.reason, FW_REASON_TIMING);
    assert_int_equal(res.slide, k + 1);
    assert_int_equal(res.scissor, k / 2 + 1);
    assert_false(res.accel);
    if (fabs(res.ratio - want) > 0.02 * want)
        fail_msg("ratio %g, by hand %g", res.ratio, want);
    /* Half as fast passes. */
    const double half[6] = {0, 0.004, 1.004, 0, 0, 0};
    assert_int_equal(fw_traj_push(&t, &G, &lim, half, 50000, false, &res), 0);
}

/* From rest, a point the slides could reach in speed but not that quickly: the acceleration is
 * named.  Setpoints go from rest to v at once; measured over 10 segments (slide_check.h), that
 * is v / 10 ms. */
static void test_timing_names_acceleration(void **state)
{
    (void)state;
    static fw_traj t;
    const double p0[6] = {0, 0, 1.0, 0, 0, 0}, p1[6] = {0, 0.0005, 1.0005, 0, 0, 0};
    start(&t, p0);
    double dq;
    const int k = fastest_slide(p0, p1, &dq);
    const double v = dq / 0.05, want = v / 0.01 / LIM.slide_amax;
    assert_true(v < 0.5 * LIM.slide_vmax && want > 1.2);
    fw_plan_result res;
    assert_int_equal(fw_traj_push(&t, &G, &LIM, p1, 50000, false, &res), -1);
    assert_int_equal(res.reason, FW_REASON_TIMING);
    assert_int_equal(res.slide, k + 1);
    assert_true(res.accel);
    if (fabs(res.ratio - want) > 0.02 * want)
        fail_msg("ratio %g, by hand %g", res.ratio, want);
}

/* A dropped trajectory holds nothing and takes nothing until the next one starts. */
static void test_drop(void **state)
{
    (void)state;
    static fw_traj t;
    const double p0[6] = {0, 0, 1.0, 0, 0, 0};
    start(&t, p0);
    fw_plan_result res;
    for (unsigned i = 0; i < 5; ++i) {
        const double p[6] = {0, 0, 1.0 + 1e-5 * (i + 1), 0, 0, 0};
        assert_int_equal(fw_traj_push(&t, &G, &LIM, p, 50000, false, &res), 0);
    }
    fw_traj_drop(&t);
    assert_int_equal(fw_traj_depth(&t), 0);
    assert_int_equal(fw_traj_free(&t), FW_TRAJ_CAPACITY);
    const double p[6] = {0, 0, 1.0001, 0, 0, 0};
    assert_int_equal(fw_traj_push(&t, &G, &LIM, p, 50000, false, &res), -1);
    assert_int_equal(res.reason, FW_REASON_STATE);
    start(&t, p0);
    assert_int_equal(fw_traj_push(&t, &G, &LIM, p, 50000, false, &res), 0);
    assert_int_equal(fw_traj_end_us(&t), 50000);
}

static void test_queue_full(void **state)
{
    (void)state;
    static fw_traj t;
    const double p0[6] = {0, 0, 1.0, 0, 0, 0};
    start(&t, p0);
    fw_plan_result res;
    for (unsigned i = 0; i < FW_TRAJ_CAPACITY; ++i) {
        const double p[6] = {0, 0, 1.0 + 1e-5 * (i + 1), 0, 0, 0};
        assert_int_equal(fw_traj_push(&t, &G, &LIM, p, 50000, false, &res), 0);
    }
    assert_int_equal(fw_traj_free(&t), 0);
    const double p[6] = {0, 0, 1.001, 0, 0, 0};
    assert_int_equal(fw_traj_push(&t, &G, &LIM, p, 50000, false, &res), -1);
    assert_int_equal(res.reason, FW_REASON_QUEUE_FULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_smooth_accepted),
        cmocka_unit_test(test_too_fast_refused_atomically),
        cmocka_unit_test(test_queue_full),
        cmocka_unit_test(test_timing_names_speed),
        cmocka_unit_test(test_timing_names_acceleration),
        cmocka_unit_test(test_drop),
    };
    return cmocka_run_group_tests(tests, setup, NULL);
}
