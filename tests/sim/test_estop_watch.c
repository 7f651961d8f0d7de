/* tse-sim's e-stop step log (host_tools/tse_sim/estop_watch.h): a step between an e-stop and its
 * clearing is reported, once; steps after the clearing (legitimate motion: enable, home, move)
 * are not; neither are steps before the e-stop.  The ticks follow the plant's convention (a step
 * interrupt after the control call at tick t steps at t, t + 1, ...). */
#include <setjmp.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "estop_watch.h"

static void test_window(void **state)
{
    (void)state;
    /* E-stop seen at tick 1000, cleared at tick 5000. */
    assert_false(estop_step_held(1000, 5000, 999));  /* before the e-stop */
    assert_true(estop_step_held(1000, 5000, 1000));  /* the first step interrupt after it */
    assert_true(estop_step_held(1000, 5000, 3000));
    assert_true(estop_step_held(1000, 5000, 4999));  /* the last one before the clear */
    assert_false(estop_step_held(1000, 5000, 5000)); /* after the clearing call */
    assert_false(estop_step_held(1000, 5000, 900000));
    /* Not cleared yet: every later step counts. */
    assert_true(estop_step_held(1000, UINT64_MAX, 900000));
}

static void test_step_while_held_is_reported_once(void **state)
{
    (void)state;
    estop_watch w;
    estop_watch_init(&w);
    uint64_t after = 0;
    assert_false(estop_watch_pulse(&w, 800, &after)); /* no e-stop yet */
    estop_watch_taken(&w, 1000);
    assert_false(estop_watch_pulse(&w, 800, &after)); /* the last step before it, seen again */
    assert_true(estop_watch_pulse(&w, 1200, &after));
    assert_int_equal(after, 200);
    assert_false(estop_watch_pulse(&w, 1200, &after)); /* the same step, seen at the next call */
    assert_true(estop_watch_pulse(&w, 1500, &after));   /* a further one */
    assert_int_equal(after, 500);                       /* measured from the e-stop */
}

static void test_steps_after_the_clear_are_not(void **state)
{
    (void)state;
    estop_watch w;
    estop_watch_init(&w);
    uint64_t after = 0;
    estop_watch_taken(&w, 1000);
    assert_false(estop_watch_pulse(&w, 900, &after));
    /* Cleared at 5000 (CLEAR_FAULT), then enabled, homed and moved: steps go on for a long time. */
    estop_watch_cleared(&w, 5000);
    for (uint64_t t = 5000; t < 2000000; t += 37)
        if (estop_watch_pulse(&w, t, &after))
            fail_msg("step at %llu reported after the clear", (unsigned long long)t);
    /* A step taken before the clear but first seen at the clearing call is still reported. */
    estop_watch_init(&w);
    estop_watch_taken(&w, 1000);
    estop_watch_cleared(&w, 5000);
    assert_true(estop_watch_pulse(&w, 4990, &after));
    assert_int_equal(after, 3990);
    /* A second clear does not move the first one's end. */
    estop_watch_cleared(&w, 9000);
    assert_false(estop_watch_pulse(&w, 6000, &after));
}

static void test_a_second_estop_opens_a_new_window(void **state)
{
    (void)state;
    estop_watch w;
    estop_watch_init(&w);
    uint64_t after = 0;
    estop_watch_taken(&w, 1000);
    estop_watch_cleared(&w, 5000);
    assert_false(estop_watch_pulse(&w, 7000, &after)); /* legitimate motion */
    estop_watch_taken(&w, 8000);
    assert_false(estop_watch_pulse(&w, 7990, &after)); /* the last step before the new e-stop */
    assert_true(estop_watch_pulse(&w, 8003, &after));
    assert_int_equal(after, 3);
    estop_watch_cleared(&w, 9000);
    assert_false(estop_watch_pulse(&w, 9100, &after));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_window),
        cmocka_unit_test(test_step_while_held_is_reported_once),
        cmocka_unit_test(test_steps_after_the_clear_are_not),
        cmocka_unit_test(test_a_second_estop_opens_a_new_window),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
