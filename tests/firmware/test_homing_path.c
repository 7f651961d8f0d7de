/* Homing's final joint move is validated before its first step (fw/joint_path.h; issue 24, point
 * 5): with a switch the parameter check would refuse (home_sw_1 = 0.475 m, the others at 0.2 m:
 * from 12.8 % of the way home the slides have no valid pose), written past the check, homing ends
 * in a homing fault, not homed, its slides where the switches left them. */
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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_joint_move_outside_the_workspace_faults),
        cmocka_unit_test(test_default_switches_home),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
