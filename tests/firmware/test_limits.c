/* The limits a parameter set gives: what a controller adopts, the step generator's ceiling worked
 * out by hand, and refusals that leave the outputs alone. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "fake_hal.h"
#include "fw/limits.h"
#include "fw/proto.h"

#define STEP_HZ 100000u
#define SEGMENT_HZ 1000u

/* A controller booted on the defaults (empty storage) holds exactly what the function derives. */
static void test_defaults_match_controller(void **state)
{
    (void)state;
    static fake_hal f;
    static fw_controller_mem mem;
    fw_hal hal;
    fake_hal_init(&f, &hal);
    const fw_config cfg = {1, SEGMENT_HZ, STEP_HZ, NULL, NULL, NULL};
    const fw_controller *c = fw_init(&mem, &hal, &cfg);
    assert_non_null(c);

    fw_param_set s;
    fw_params_default(&s);
    tse_geometry g;
    fw_limits lim;
    assert_int_equal(fw_limits_from_params(&s, STEP_HZ, SEGMENT_HZ, &g, &lim), 0);
    assert_memory_equal(&g, fw_geometry_of(c), sizeof g);
    assert_memory_equal(&lim, fw_limits_of(c), sizeof lim);
}

/* The defaults by hand: 1.28M steps/m, 200k steps/s, 150 mm/s asked.  At 100 kHz and 1 kHz a
 * segment has 100 ticks; a 5 us DIR set-up is half a tick, rounded up to 1, plus the one of
 * margin: 2; the step spacing is ceil(100k / 200k) = 1 tick.  A reversing segment then holds 98
 * steps: 98 * 1000 / 1.28M = 76.5625 mm/s, 90 % of which is 68.90625 mm/s, below both the rate
 * limit's 0.9 * 200k / 1.28M = 140.625 mm/s and the 150 mm/s asked. */
static void test_defaults_by_hand(void **state)
{
    (void)state;
    fw_param_set s;
    fw_params_default(&s);
    tse_geometry g;
    fw_limits lim;
    assert_int_equal(fw_limits_from_params(&s, STEP_HZ, SEGMENT_HZ, &g, &lim), 0);
    assert_true(fabs(lim.slide_vmax - 0.06890625) < 1e-12);
    assert_true(fabs(lim.slide_amax - 1.0) < 1e-12);
    assert_true(fabs(lim.plate_vmax - 0.3) < 1e-12);
    assert_true(fabs(lim.plate_amax - 1.0) < 1e-12);
    assert_true(fabs(lim.plate_jmax - 10.0) < 1e-12);
    assert_true(fabs(lim.plate_wmax - 0.5) < 1e-12);
    assert_true(fabs(lim.plate_dwmax - 2.0) < 1e-12);
    assert_true(lim.segment_hz == 1000.0);
    stepgen_config sc;
    assert_int_equal(fw_stepgen_config_from_params(&s, STEP_HZ, SEGMENT_HZ, &sc), 0);
    assert_int_equal(sc.ticks_per_segment, 100);
    assert_int_equal(sc.dir_setup_ticks, 2);
    assert_int_equal(sc.min_step_interval, 1);
    /* The step generator's limit is the one in effect, and the limits say so. */
    assert_int_equal(lim.vmax_by, FW_LIMIT_STEP_GENERATOR);
    fw_speed_limit v;
    assert_int_equal(fw_speed_limit_from_params(&s, STEP_HZ, SEGMENT_HZ, &v), 0);
    assert_int_equal(v.by, FW_LIMIT_STEP_GENERATOR);
    assert_int_equal(v.segment_steps, 98);
    assert_true(fabs(v.vmax - 0.06890625) < 1e-12 && fabs(v.by_steps - 0.06890625) < 1e-12);
    assert_true(fabs(v.by_param - 0.15) < 1e-12);

    /* A slower slide limit than the generator's binds instead: 50 mm/s. */
    s.v[FP_SLIDE_VMAX] = 50000;
    assert_int_equal(fw_limits_from_params(&s, STEP_HZ, SEGMENT_HZ, &g, &lim), 0);
    assert_true(fabs(lim.slide_vmax - 0.05) < 1e-12);
    assert_int_equal(lim.vmax_by, FW_LIMIT_SLIDE_VMAX);
    /* A step rate limit of 20k/s: 5 ticks between steps, 98 / 5 = 19 steps a reversing segment
     * (0.9 * 19000 / 1.28M = 13.359375 mm/s), below the rate's own 0.9 * 20k / 1.28M = 14.0625. */
    s.v[FP_STEP_RATE_MAX] = 20000;
    assert_int_equal(fw_limits_from_params(&s, STEP_HZ, SEGMENT_HZ, &g, &lim), 0);
    assert_true(fabs(lim.slide_vmax - 0.013359375) < 1e-12);
    assert_int_equal(lim.vmax_by, FW_LIMIT_STEP_GENERATOR);

    /* At the board's and tse-sim's 200 kHz: 200 ticks a segment, the 5 us set-up 1 tick + 1, so
     * 198 steps: 0.9 * 198000 / 1.28M = 139.21875 mm/s, below slide_vmax's 150 (and the 140.625
     * of 0.9 step_rate_max / steps_per_m). */
    fw_params_default(&s);
    assert_int_equal(fw_speed_limit_from_params(&s, FW_STEP_HZ, FW_SEGMENT_HZ, &v), 0);
    assert_int_equal(v.segment_steps, 198);
    assert_int_equal(v.by, FW_LIMIT_STEP_GENERATOR);
    assert_true(fabs(v.vmax - 0.13921875) < 1e-12);
}

/* The step generator's limit is always below FW_STEP_RATE_MARGIN x step_rate_max / steps_per_m,
 * the rate limit alone: a segment of P ticks holds floor((P - set-up) / ceil(step_hz / rate))
 * steps, and with a set-up of at least a tick that is under P rate / step_hz.  Over rates, set-ups
 * and both configurations. */
static void test_generator_below_rate(void **state)
{
    (void)state;
    static const uint32_t hz[] = {STEP_HZ, FW_STEP_HZ};
    static const int32_t rates[] = {1000, 7000, 33333, 99999, 100000, 100001, 150000, 199999, 200000, 500000};
    static const int32_t dirs[] = {0, 1, 5000, 10000, 123457, 400000};
    for (size_t h = 0; h < 2; ++h)
        for (size_t i = 0; i < sizeof rates / sizeof rates[0]; ++i)
            for (size_t j = 0; j < sizeof dirs / sizeof dirs[0]; ++j) {
                fw_param_set s;
                fw_params_default(&s);
                s.v[FP_STEP_PULSE_NS] = 100;
                s.v[FP_STEP_RATE_MAX] = rates[i];
                s.v[FP_DIR_SETUP_NS] = dirs[j];
                s.v[FP_SLIDE_VMAX] = 2000000; /* out of the way */
                fw_speed_limit v;
                if (fw_speed_limit_from_params(&s, hz[h], SEGMENT_HZ, &v) != 0)
                    continue; /* no room for a step: refused, tested elsewhere */
                const double by_rate = 0.9 * rates[i] / 1280000.0;
                if (!(v.by_steps < by_rate))
                    fail_msg("rate %d, set-up %d ns at %u Hz: %.9g m/s, not below %.9g", rates[i], dirs[j], hz[h],
                             (double)v.by_steps, by_rate);
                assert_int_equal(v.by, FW_LIMIT_STEP_GENERATOR);
            }
}

/* The rules the step generator's timing asks, each worked by hand at 100 kHz (10 us ticks) and
 * 1 kHz segments, with the parameter blamed. */
static void test_timing_rules(void **state)
{
    (void)state;
    static const struct {
        int id;
        int32_t value;
        uint32_t segment_hz;
        fw_param_rule rule;
        int blamed;
    } cases[] = {
        {FP_STEP_PULSE_NS, 9999, SEGMENT_HZ, FW_RULE_PULSE_LOW, FP_STEP_PULSE_NS},     /* ends in its tick */
        {FP_STEP_PULSE_NS, 10000, SEGMENT_HZ, FW_RULE_PULSE_PERIOD, FP_STEP_PULSE_NS}, /* a whole tick */
        {FP_STEP_PULSE_NS, 5001, SEGMENT_HZ, FW_RULE_PULSE_LOW, FP_STEP_PULSE_NS},     /* 4999 ns low */
        {FP_STEP_PULSE_NS, 5000, SEGMENT_HZ, FW_RULE_NONE, -1},                        /* 5000 ns low */
        {FP_DIR_SETUP_NS, 980000, SEGMENT_HZ, FW_RULE_NONE, -1},              /* 98 + 1 ticks, 1 left */
        {FP_DIR_SETUP_NS, 980001, SEGMENT_HZ, FW_RULE_DIR_SETUP_ROOM, FP_DIR_SETUP_NS}, /* 99 + 1 */
        {FP_L, 0, SEGMENT_HZ, FW_RULE_RANGE, FP_L},                  /* the set's own rules first */
        {FP_ALPHA_MIN, 1300000, SEGMENT_HZ, FW_RULE_ALPHA_ORDER, FP_ALPHA_MAX},
        {FP_STEP_PULSE_NS, 2000, 3000, FW_RULE_CONFIG, -1},          /* 3 kHz does not divide 100 kHz */
        {FP_STEP_PULSE_NS, 2000, 0, FW_RULE_CONFIG, -1},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        fw_param_set s;
        fw_params_default(&s);
        s.v[cases[i].id] = cases[i].value;
        const fw_param_fault f = fw_params_judge_config(&s, STEP_HZ, cases[i].segment_hz);
        if (f.rule != cases[i].rule || f.id != cases[i].blamed)
            fail_msg("case %zu: rule %d on %d, by hand %d on %d", i, f.rule, f.id, cases[i].rule, cases[i].blamed);
        stepgen_config sc;
        if (cases[i].rule >= FW_RULE_PULSE_PERIOD)
            assert_int_equal(fw_stepgen_config_from_params(&s, STEP_HZ, cases[i].segment_hz, &sc), cases[i].rule);
    }
    /* The ticks behind them: ceil(100k / rate) between steps, ceil(dir 100k / 1e9) + 1 of set-up. */
    assert_int_equal(fw_step_interval_ticks(200000, STEP_HZ), 1);
    assert_int_equal(fw_step_interval_ticks(100000, STEP_HZ), 1);
    assert_int_equal(fw_step_interval_ticks(99999, STEP_HZ), 2);
    assert_int_equal(fw_step_interval_ticks(1000, STEP_HZ), 100);
    assert_int_equal(fw_dir_setup_ticks(0, STEP_HZ), 1);
    assert_int_equal(fw_dir_setup_ticks(1, STEP_HZ), 2);
    assert_int_equal(fw_dir_setup_ticks(10000, STEP_HZ), 2);
    assert_int_equal(fw_dir_setup_ticks(10001, STEP_HZ), 3);
    assert_int_equal(fw_dir_setup_ticks(5000, FW_STEP_HZ), 2);
}

/* The words of the step generator's limit say the margin the code uses. */
static void test_margin_words(void **state)
{
    (void)state;
    char want[32];
    snprintf(want, sizeof want, "%.1f x the steps", (double)FW_STEP_RATE_MARGIN);
    const char *w = proto_code_words(proto_slide_limits, FW_LIMIT_STEP_GENERATOR);
    assert_non_null(w);
    if (!strstr(w, want))
        fail_msg("'%s' does not say '%s'", w, want);
}

/* Each way a set or a configuration is refused gives -1 and leaves both outputs as they were. */
static void test_refused_leaves_outputs(void **state)
{
    (void)state;
    struct {
        int id;
        int32_t value;
        uint32_t step_hz, segment_hz;
    } cases[] = {
        {FP_L, 0, STEP_HZ, SEGMENT_HZ},                   /* out of range */
        {FP_ALPHA_MIN, 1300000, STEP_HZ, SEGMENT_HZ},     /* stops crossed: no geometry */
        {FP_STEP_PULSE_NS, 10000, STEP_HZ, SEGMENT_HZ},   /* a 10 us pulse in a 10 us tick */
        {FP_DIR_SETUP_NS, 1000000, STEP_HZ, SEGMENT_HZ},  /* 1 ms set-up in a 1 ms segment */
        {-1, 0, STEP_HZ, 0},                              /* no segment rate */
        {-1, 0, STEP_HZ, 3000},                           /* not a divisor of the step rate */
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        fw_param_set s;
        fw_params_default(&s);
        if (cases[i].id >= 0)
            s.v[cases[i].id] = cases[i].value;
        tse_geometry g, g0;
        fw_limits lim, lim0;
        memset(&g, 0x5A, sizeof g);
        memset(&lim, 0x5A, sizeof lim);
        g0 = g;
        lim0 = lim;
        if (fw_limits_from_params(&s, cases[i].step_hz, cases[i].segment_hz, &g, &lim) != -1)
            fail_msg("case %zu accepted", i);
        assert_memory_equal(&g, &g0, sizeof g);
        assert_memory_equal(&lim, &lim0, sizeof lim);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_defaults_match_controller),
        cmocka_unit_test(test_defaults_by_hand),
        cmocka_unit_test(test_refused_leaves_outputs),
        cmocka_unit_test(test_generator_below_rate),
        cmocka_unit_test(test_timing_rules),
        cmocka_unit_test(test_margin_words),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
