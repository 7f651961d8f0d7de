/* Timed trajectory points: validation on arrival, flow control, atomic refusal. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>

#include "fw/traj.h"

static tse_geometry G;
static const fw_limits LIM = {0.2, 1.0, 0.3, 1.0, 10.0, 0.5, 2.0, 1000.0};

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
    };
    return cmocka_run_group_tests(tests, setup, NULL);
}
