/* Parameter table, checks and the storage record. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "fw/limits.h"
#include "fw/params.h"
#include "fw/types.h"

static void test_defaults_are_the_prototype(void **state)
{
    (void)state;
    fw_param_set s;
    fw_params_default(&s);
    assert_int_equal(fw_params_check(&s), -1);
    tse_params p;
    fw_params_kinematics(&s, &p);
    /* kinematics.md: L 1.727, k1 0.2647, eta 30 deg, alpha stops asin(0.324/L), asin(1.619/L). */
    assert_true(fabs(p.L - 1.727) < 1e-12);
    assert_true(fabs(p.k1 - 0.2647) < 1e-12);
    assert_true(fabs(p.eta - TSE_PI / 6) < 1e-6);
    assert_true(fabs(p.alpha_min - asin(0.324 / 1.727)) < 1e-6);
    assert_true(fabs(p.alpha_max - asin(1.619 / 1.727)) < 1e-6);
    assert_true(fabs(p.s_max - 0.90) < 1e-12);
    for (int i = 0; i < FP_COUNT; ++i) {
        assert_non_null(fw_param_table[i].name);
        assert_true(fw_param_table[i].min <= fw_param_table[i].def && fw_param_table[i].def <= fw_param_table[i].max);
    }
}

static void test_set_one(void **state)
{
    (void)state;
    fw_param_set s, before;
    fw_params_default(&s);
    before = s;
    assert_int_equal(fw_params_set_one(&s, FP_COUNT, 1), FW_REASON_PARAM_UNKNOWN);
    assert_int_equal(fw_params_set_one(&s, FP_L, 0), FW_REASON_PARAM_RANGE);
    /* In range alone, invalid as a set: alpha_min above alpha_max. */
    assert_int_equal(fw_params_set_one(&s, FP_ALPHA_MIN, 1300000), FW_REASON_PARAM_SET);
    assert_int_equal(fw_params_set_one(&s, FP_S_MIN, 900000), FW_REASON_PARAM_SET);
    assert_memory_equal(&s, &before, sizeof s);
    assert_int_equal(fw_params_set_one(&s, FP_WATCHDOG_MS, 250), 0);
    assert_int_equal(s.v[FP_WATCHDOG_MS], 250);
}

/* The parameters the board needs: their defaults, ranges and the checks on the set. */
static void test_board_parameters(void **state)
{
    (void)state;
    fw_param_set s, before;
    fw_params_default(&s);
    /* Appended after homing_backoff (ids travel on the wire). */
    assert_int_equal(FP_HOME_SW_1, FP_HOMING_BACKOFF + 1);
    assert_int_equal(FP_CAN_KBPS, FP_COUNT - 1);
    for (int k = 0; k < 6; ++k)
        assert_int_equal(s.v[FP_HOME_SW_1 + k], 200000);
    /* The Leadshine DM542's timing (User's Manual V1.0, section 10, Figure 11; docs/board.md):
     * a pulse of at least 2.5 us (t3), DIR at least 5 us ahead of its edge (t2); and the
     * defaults taken by the board's 200 kHz step interrupts (1 kHz segments). */
    assert_true(s.v[FP_STEP_PULSE_NS] >= 2500);
    assert_true(s.v[FP_DIR_SETUP_NS] >= 5000);
    stepgen_config sc;
    assert_int_equal(fw_stepgen_config_from_params(&s, 200000, 1000, &sc), 0);
    /* docs/board.md's set with margin on both (1/32 microstepping): a slide steps at most every
     * other 5 us interrupt, so a 3.5 us pulse fits; at the default rate it would not. */
    fw_param_set m = s;
    m.v[FP_STEPS_PER_M] = 640000;
    m.v[FP_STEP_RATE_MAX] = 100000;
    m.v[FP_STEP_PULSE_NS] = 3500;
    assert_int_equal(fw_stepgen_config_from_params(&m, 200000, 1000, &sc), 0);
    assert_int_equal(sc.min_step_interval, 2);
    m.v[FP_STEP_RATE_MAX] = s.v[FP_STEP_RATE_MAX];
    assert_int_equal(fw_stepgen_config_from_params(&m, 200000, 1000, &sc), -1);
    assert_int_equal(s.v[FP_CAN_KBPS], 500);
    before = s;
    /* CAN: four rates, anything else out of range, naming the parameter. */
    const int32_t rates[] = {125, 250, 500, 1000}, bad_rates[] = {124, 126, 300, 800, 999, 1001, 0};
    for (size_t i = 0; i < sizeof rates / sizeof rates[0]; ++i) {
        assert_int_equal(fw_params_set_one(&s, FP_CAN_KBPS, rates[i]), 0);
        assert_int_equal(s.v[FP_CAN_KBPS], rates[i]);
    }
    for (size_t i = 0; i < sizeof bad_rates / sizeof bad_rates[0]; ++i) {
        assert_int_equal(fw_params_set_one(&s, FP_CAN_KBPS, bad_rates[i]), FW_REASON_PARAM_RANGE);
        fw_param_set t = s;
        t.v[FP_CAN_KBPS] = bad_rates[i];
        assert_int_equal(fw_params_check(&t), FP_CAN_KBPS);
    }
    assert_int_equal(s.v[FP_CAN_KBPS], 1000);
    /* A switch outside the stroke [0, 0.9 m] is refused, naming it. */
    assert_int_equal(fw_params_set_one(&s, FP_HOME_SW_3, 900001), FW_REASON_PARAM_SET);
    assert_int_equal(fw_params_set_one(&s, FP_HOME_SW_3, 900000), 0);
    fw_param_set t = s;
    t.v[FP_HOME_SW_5] = 950000;
    assert_int_equal(fw_params_check(&t), FP_HOME_SW_5);
    /* The switches reachable together.  Prototype: l0 = 0.2647 * 1.727 = 0.45714 m, alpha_max =
     * asin(1.619 / 1.727), cos alpha_max = sqrt(1 - 0.937464^2) = 0.348083, so a scissor's width
     * must stay >= 2 l0 cos alpha_max = 0.318243 m; with eta = 30 deg, w = sqrt(sA^2 + sB^2 +
     * sA sB): both slides at 0.1835 m give 0.317831 (too narrow), at 0.1840 m 0.318697. */
    s = before;
    assert_int_equal(fw_params_set_one(&s, FP_HOME_SW_1, 183500), 0); /* with B at 0.2: 0.332 */
    assert_int_equal(fw_params_set_one(&s, FP_HOME_SW_2, 183500), FW_REASON_PARAM_SET);
    t = s;
    t.v[FP_HOME_SW_2] = 183500;
    assert_int_equal(fw_params_check(&t), FP_HOME_SW_1);
    assert_int_equal(fw_params_set_one(&s, FP_HOME_SW_2, 184000), 0);
    /* Per scissor, not per slide: 0.1 m and 0.3 m give sqrt(0.13) = 0.3606. */
    assert_int_equal(fw_params_set_one(&s, FP_HOME_SW_4, 300000), 0);
    assert_int_equal(fw_params_set_one(&s, FP_HOME_SW_3, 100000), 0);
    /* The timing parameters' own ranges (what fits the step interrupt is the controller's check). */
    assert_int_equal(fw_params_set_one(&s, FP_STEP_PULSE_NS, 99), FW_REASON_PARAM_RANGE);
    assert_int_equal(fw_params_set_one(&s, FP_DIR_SETUP_NS, -1), FW_REASON_PARAM_RANGE);
    assert_int_equal(fw_params_set_one(&s, FP_DIR_SETUP_NS, 0), 0);
}

static void test_record(void **state)
{
    (void)state;
    fw_param_set s, back;
    fw_params_default(&s);
    s.v[FP_SLIDE_VMAX] = 123456;
    uint8_t buf[256];
    const size_t n = fw_params_serialize(&s, buf, sizeof buf);
    assert_true(n > 0);
    assert_int_equal(fw_params_serialize(&s, buf, n - 1), 0);
    fw_params_default(&back);
    assert_int_equal(fw_params_deserialize(&back, buf, n), 0);
    assert_memory_equal(&back, &s, sizeof s);
    /* Any flipped bit, or a short record, is refused and changes nothing. */
    for (size_t i = 0; i < n; ++i) {
        buf[i] ^= 0x10;
        fw_param_set t;
        fw_params_default(&t);
        const fw_param_set t0 = t;
        assert_int_equal(fw_params_deserialize(&t, buf, n), -1);
        assert_memory_equal(&t, &t0, sizeof t);
        buf[i] ^= 0x10;
    }
    assert_int_equal(fw_params_deserialize(&back, buf, n - 1), -1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_defaults_are_the_prototype),
        cmocka_unit_test(test_set_one),
        cmocka_unit_test(test_board_parameters),
        cmocka_unit_test(test_record),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
