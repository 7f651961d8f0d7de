/* Homing's final joint move is validated before its first step (fw/joint_path.h; issue 24, point
 * 5): with a switch the parameter check would refuse (home_sw_1 = 0.475 m, the others at 0.2 m:
 * from 12.8 % of the way home the slides have no valid pose), written past the check, homing ends
 * in a homing fault, not homed, its slides where the switches left them.  The check runs in the
 * controller's thread while the slides rest on their switches. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "harness.h"

static void test_joint_move_outside_the_workspace_faults(void **state)
{
    (void)state;
    start();
    cmd(PM_ENABLE);
    run(20);
    assert_int_equal(fw_state_of(C), FW_STATE_IDLE);
    /* The switch's position as homing reads it; the plant's switch stays where it is. */
    fw_testing_force_param(C, FP_HOME_SW_1, 475000);
    cmd(PM_HOME);
    run(100);
    for (int i = 0; i < 200 && fw_state_of(C) == FW_STATE_HOMING; ++i)
        run(100);
    assert_int_equal(fw_state_of(C), FW_STATE_FAULT);
    assert_int_equal(fw_fault_of(C), FW_FAULT_HOMING);
    assert_false(fw_homed_of(C));
    /* No step toward home: every slide at its switch's release edge, a step or two above it. */
    for (int k = 0; k < 6; ++k)
        assert_true(F.steps[k] > FAKE_SWITCH_AT && F.steps[k] <= FAKE_SWITCH_AT + 4);
}

/* The default switches: homing ends homed at the home pose (the check passes what it should). */
static void test_default_switches_home(void **state)
{
    (void)state;
    start();
    home();
    assert_int_equal(fw_fault_of(C), FW_FAULT_NONE);
}

/* Control periods alone, as when the thread does not run. */
static void ticks_alone(unsigned n)
{
    for (unsigned i = 0; i < n; ++i)
        fake_tick_alone(&F, C);
}

/* Homing until the slides rest on their switches' edges and the path waits for its check. */
static void home_to_the_check(void)
{
    start();
    cmd(PM_ENABLE);
    run(20);
    cmd(PM_HOME);
    /* A period at a time (run() takes ten), the host's heartbeat every ten. */
    for (int i = 0; i < 20000 && now().home_phase != HOME_PATH_CHECK; ++i) {
        if (i % 10 == 0)
            heartbeat();
        fake_run(&F, C, 1);
    }
    assert_int_equal(now().home_phase, HOME_PATH_CHECK);
    assert_int_equal(fw_state_of(C), FW_STATE_HOMING);
}

/* The path's check (a quarter of a million instructions on the board) runs in the thread, not in
 * the control tick (issue 23: a tick within 50 us): ticks alone leave homing at rest waiting for
 * it however long; the thread's next poll checks it and the tick then starts the joint move. */
static void test_the_path_is_checked_by_the_thread(void **state)
{
    (void)state;
    home_to_the_check();
    int32_t at[6];
    memcpy(at, F.steps, sizeof at);
    ticks_alone(500);
    assert_int_equal(now().home_phase, HOME_PATH_CHECK);
    assert_int_equal(fw_state_of(C), FW_STATE_HOMING);
    assert_memory_equal(at, F.steps, sizeof at);
    heartbeat(); /* the thread reads the bus again: the host must not look silent */
    fw_poll(C);
    ticks_alone(1);
    assert_int_equal(now().home_phase, HOME_TO_POSE);
    for (int i = 0; i < 200 && fw_state_of(C) == FW_STATE_HOMING; ++i)
        run(100);
    assert_int_equal(fw_state_of(C), FW_STATE_IDLE);
    assert_true(fw_homed_of(C));
}

/* A STOP while the path waits for its check ends homing there, not homed, no fault; a new homing
 * afterwards asks for a check of its own and homes. */
static void test_stop_while_the_check_waits(void **state)
{
    (void)state;
    home_to_the_check();
    cmd(PM_STOP);
    run(20);
    assert_int_equal(fw_state_of(C), FW_STATE_IDLE);
    assert_int_equal(fw_fault_of(C), FW_FAULT_NONE);
    assert_false(fw_homed_of(C));
    cmd(PM_HOME);
    run(20);
    assert_int_equal(fw_state_of(C), FW_STATE_HOMING);
    for (int i = 0; i < 200 && fw_state_of(C) == FW_STATE_HOMING; ++i)
        run(100);
    assert_int_equal(fw_state_of(C), FW_STATE_IDLE);
    assert_true(fw_homed_of(C));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_joint_move_outside_the_workspace_faults),
        cmocka_unit_test(test_default_switches_home),
        cmocka_unit_test(test_the_path_is_checked_by_the_thread),
        cmocka_unit_test(test_stop_while_the_check_waits),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
