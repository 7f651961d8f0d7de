/* Parameter table, checks and the storage record. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

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
        cmocka_unit_test(test_record),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
