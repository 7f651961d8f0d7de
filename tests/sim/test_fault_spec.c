/* tse-sim --fault SPEC: what each item sets in the fault layer's configuration (times in
 * microseconds, slides as masks), and a clear refusal, naming the item and the rule, for every
 * kind of bad spec. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "fault_spec.h"

static fault_plan P;
static char err[256];

static void ok(const char *spec)
{
    err[0] = '\0';
    if (fault_spec_parse(spec, &P, err, sizeof err) != 0)
        fail_msg("'%s' refused: %s", spec, err);
}

static void refused(const char *spec, const char *says)
{
    err[0] = '\0';
    if (fault_spec_parse(spec, &P, err, sizeof err) == 0)
        fail_msg("'%s' taken", spec);
    if (!strstr(err, says))
        fail_msg("'%s': '%s' does not say '%s'", spec, err, says);
}

static void test_every_item(void **state)
{
    (void)state;
    ok("drop=0.01,dup=0.02,reorder=0.03,delay=0.04,corrupt=0.05,delay_ms=35,seed=7,silence=5+2,busoff=8+0.1,"
       "estop=12,limit=3@4+0.5,stall=2@6");
    const double p[FAULT_CAN_KINDS] = {0.01, 0.02, 0.03, 0.04, 0.05};
    for (int k = 0; k < FAULT_CAN_KINDS; ++k)
        assert_true(P.can.p[k] == p[k]);
    assert_int_equal(P.can.delay_us, 35000);
    assert_true(P.can.seed == 7);
    assert_true(P.can.silence.from_us == 5000000 && P.can.silence.until_us == 7000000);
    assert_true(P.can.bus_off.from_us == 8000000 && P.can.bus_off.until_us == 8100000);
    assert_true(P.inputs.estop.from_us == 12000000 && P.inputs.estop.until_us == FAULT_FOREVER);
    assert_true(P.inputs.limit.from_us == 4000000 && P.inputs.limit.until_us == 4500000);
    assert_int_equal(P.inputs.limit_mask, 1u << (8 + 2)); /* slide 3's high-end switch */
    assert_true(P.stepper.stall.from_us == 6000000 && P.stepper.stall.until_us == FAULT_FOREVER);
    assert_int_equal(P.stepper.stall_mask, 1u << 1);
    for (int k = 0; k < HAL_AXES; ++k)
        assert_int_equal(P.stepper.miss[k], 0);
}

static void test_defaults_and_numbers(void **state)
{
    (void)state;
    ok("drop=1");
    assert_true(P.can.p[FAULT_DROP] == 1.0);
    for (int k = 1; k < FAULT_CAN_KINDS; ++k)
        assert_true(P.can.p[k] == 0.0);
    assert_true(P.can.seed == 1);
    assert_int_equal(P.can.delay_us, 20000);
    /* Nothing else holds, ever. */
    const fault_window *w[] = {&P.can.silence, &P.can.bus_off, &P.inputs.estop, &P.inputs.limit, &P.stepper.stall};
    for (size_t i = 0; i < sizeof w / sizeof w[0]; ++i)
        assert_true(fault_window_empty(w[i]));
    assert_int_equal(P.inputs.limit_mask, 0);
    assert_int_equal(P.stepper.stall_mask, 0);
    /* Exponents, their signs included, belong to the numbers. */
    ok("delay=1e-2,silence=1e+1+2.5e-1,seed=18446744073709551615,dup=0.99");
    assert_true(P.can.p[FAULT_DELAY] == 0.01);
    assert_true(P.can.silence.from_us == 10000000 && P.can.silence.until_us == 10250000);
    assert_true(P.can.seed == UINT64_MAX);
    ok("busoff=0+0.000001"); /* one microsecond from the start */
    assert_true(P.can.bus_off.from_us == 0 && P.can.bus_off.until_us == 1);
}

static void test_refusals(void **state)
{
    (void)state;
    refused("", "empty");
    refused("drop", "'drop': expected KEY=VALUE");
    refused("drop=2", "'drop=2': drop is a probability, 0..1");
    refused("corrupt=-0.1", "corrupt is a probability");
    refused("dup=x", "dup is a probability");
    refused("dup=nan", "dup is a probability");
    refused("foo=1", "unknown item 'foo' (known: drop, dup");
    refused("drop=0.1,drop=0.2", "'drop' given twice");
    refused("drop=0.6,dup=0.5", "add up to 1.1: at most 1");
    refused("drop=0.1,", "an empty item");
    refused(",drop=0.1", "an empty item");
    refused("drop=0.1,,dup=0.1", "an empty item");
    refused("delay_ms=0", "delay_ms is a whole number of milliseconds, 1..60000");
    refused("delay_ms=1.5", "delay_ms is a whole number");
    refused("delay_ms=60001", "delay_ms is a whole number");
    refused("seed=-1", "seed is a whole number");
    refused("seed=18446744073709551616", "seed is a whole number");
    refused("seed=", "seed is a whole number");
    refused("silence=5+0", "'silence=5+0': expected T or T+D, seconds after the start (T >= 0, D > 0)");
    refused("silence=5+", "expected T or T+D");
    refused("busoff=-1", "expected T or T+D");
    refused("estop=soon", "expected T or T+D");
    refused("estop=inf", "expected T or T+D");
    refused("estop=2000000", "expected T or T+D"); /* beyond a million seconds */
    refused("limit=7@1", "'limit=7@1': the slide is 1..6");
    refused("stall=0@1", "the slide is 1..6");
    refused("limit=1", "expected K@T[+D]");
    refused("stall=@1", "expected K@T[+D]");
    refused("limit=1@-1", "after @: T or T+D");
    refused("stall=2@1+x", "after @: T or T+D");
    char longer[600];
    memset(longer, 'a', sizeof longer - 1);
    longer[sizeof longer - 1] = '\0';
    refused(longer, "longer than 511 characters");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_item),
        cmocka_unit_test(test_defaults_and_numbers),
        cmocka_unit_test(test_refusals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
