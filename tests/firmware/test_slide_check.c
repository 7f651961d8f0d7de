/* The slide limit check: which slide and which limit give the worst ratio, against sequences whose
 * speeds and accelerations are worked out by hand. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "fw/slide_check.h"

/* Slide 3 (q index 3) moves 2 mm a segment (2 m/s), the others 0.5 mm (0.5 m/s), for 40 segments
 * from rest, then stops.  Worst speed: 2 m/s, slide 3.  Acceleration, the second difference over
 * 10 segments (slide_check.h): from rest the 10th setpoint gives (20 mm - 2 * 0 + 0) / (10 ms)^2
 * = 200 m/s^2, the largest (the others' 50), and the stop after the last mirrors it. */
static void feed_run(fw_slide_check *c, double vmax, double amax)
{
    const double q0[6] = {0};
    fw_slide_check_start(c, vmax, amax, 1000.0, q0);
    for (int n = 1; n <= 40; ++n) {
        double q[6];
        for (int k = 0; k < 6; ++k)
            q[k] = (k == 3 ? 0.002 : 0.0005) * n;
        fw_slide_check_feed(c, q, 0.001);
    }
    fw_slide_check_finish(c);
}

static void test_speed_worst(void **state)
{
    (void)state;
    fw_slide_check c;
    feed_run(&c, 1.0, 1000.0);
    assert_true(fabs(c.v_ratio - 2.0) < 1e-9);
    assert_true(fabs(c.a_ratio - 0.2) < 1e-9);
    assert_false(fw_slide_check_ok(&c));
    const fw_slide_worst w = fw_slide_check_worst(&c);
    assert_int_equal(w.slide, 3);
    assert_false(w.accel);
    assert_true(fabs(w.ratio - 2.0) < 1e-9);
}

static void test_acceleration_worst(void **state)
{
    (void)state;
    fw_slide_check c;
    feed_run(&c, 4.0, 100.0);
    assert_true(fabs(c.v_ratio - 0.5) < 1e-9);
    assert_true(fabs(c.a_ratio - 2.0) < 1e-9);
    const fw_slide_worst w = fw_slide_check_worst(&c);
    assert_int_equal(w.slide, 3);
    assert_true(w.accel);
    assert_true(fabs(w.ratio - 2.0) < 1e-9);
}

static void test_within_limits(void **state)
{
    (void)state;
    fw_slide_check c;
    feed_run(&c, 2.5, 250.0);
    assert_true(fw_slide_check_ok(&c));
    assert_true(fabs(c.v_ratio - 0.8) < 1e-9 && fabs(c.a_ratio - 0.8) < 1e-9);
    feed_run(&c, 2.5, 190.0);
    assert_false(fw_slide_check_ok(&c));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_speed_worst),
        cmocka_unit_test(test_acceleration_worst),
        cmocka_unit_test(test_within_limits),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
