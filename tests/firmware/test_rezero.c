/* Issue 9's two defects, as regression tests.
 * 1. A parameter that changes what a step means or the geometry (steps per metre, the homing
 *    switches, the design parameters, the angle stops, the stroke) must clear `homed`: the fuzzer's
 *    sequence (homed, DISABLE, PARAM_SET steps_per_m, ENABLE, MOVE_COMMIT) drove a slide past its
 *    stroke with the old zero read at the new scale.  The margins only judge later paths: homed
 *    stays.
 * 2. A segment the step generator could not step in its time latches FW_FAULT_STEP_OVERRUN after a
 *    controlled stop. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "harness.h"

/* Homed, then disabled with the parameter changed, then enabled: is a move still taken? */
static char move_after_change(int id, int32_t value, uint8_t *reason)
{
    home();
    assert_true(fw_homed_of(C));
    cmd(PM_DISABLE);
    run(5);
    assert_int_equal(set_param(id, value, NULL, NULL), 'a');
    cmd(PM_ENABLE);
    run(5);
    const unsigned from = F.tx_count;
    move_to(NEAR, 1000);
    run(2);
    return answer(from, proto_table[PM_MOVE_COMMIT].function, reason);
}

static void steps_per_m_clears_homed(void **state)
{
    (void)state;
    start();
    uint8_t reason = 0;
    assert_int_equal(move_after_change(FP_STEPS_PER_M, 2 * fw_param_table[FP_STEPS_PER_M].def, &reason), 'r');
    assert_int_equal(reason, FW_REASON_NOT_HOMED);
    assert_false(fw_homed_of(C));
}

static void geometry_and_stroke_clear_homed(void **state)
{
    (void)state;
    /* Each a small change that keeps the set valid. */
    const struct {
        int id;
        int32_t delta;
    } changes[] = {{FP_L, 1000},       {FP_K1, 100},       {FP_ETA, 1000},   {FP_K3, 100},  {FP_K4, 100},
                   {FP_ALPHA_MIN, -1000}, {FP_ALPHA_MAX, 1000}, {FP_S_MIN, 1000}, {FP_S_MAX, -1000}};
    for (size_t i = 0; i < sizeof changes / sizeof changes[0]; ++i) {
        start();
        uint8_t reason = 0;
        const int id = changes[i].id;
        if (move_after_change(id, fw_param_table[id].def + changes[i].delta, &reason) != 'r' ||
            reason != FW_REASON_NOT_HOMED)
            fail_msg("changing %s while homed kept the zero", fw_param_table[id].name);
    }
}

static void margins_keep_homed(void **state)
{
    (void)state;
    start();
    uint8_t reason = 0;
    assert_int_equal(move_after_change(FP_MU_MIN, fw_param_table[FP_MU_MIN].def + 1000, &reason), 'a');
    assert_true(fw_homed_of(C));
}

static void overrun_is_a_fault_with_a_controlled_stop(void **state)
{
    (void)state;
    start();
    home();
    move_to(NEAR, 1000);
    run(200);
    assert_int_equal(fw_state_of(C), FW_STATE_MOVING);
    /* As the step interrupt counts a segment it could not step in its time. */
    fw_testing_overrun(C);
    run(5);
    assert_int_equal(fw_state_of(C), FW_STATE_STOPPING);
    run(2000);
    assert_int_equal(fw_state_of(C), FW_STATE_FAULT);
    assert_int_equal(fw_fault_of(C), FW_FAULT_STEP_OVERRUN);
    /* Cleared, re-enabled and re-homed, the old count does not fault again. */
    cmd(PM_CLEAR_FAULT);
    run(5);
    home();
    assert_int_equal(fw_state_of(C), FW_STATE_IDLE);
    assert_int_equal(fw_fault_of(C), FW_FAULT_NONE);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(steps_per_m_clears_homed),
        cmocka_unit_test(geometry_and_stroke_clear_homed),
        cmocka_unit_test(margins_keep_homed),
        cmocka_unit_test(overrun_is_a_fault_with_a_controlled_stop),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
