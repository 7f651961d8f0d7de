/* The limits a parameter set gives: what a controller adopts, the step generator's ceiling worked
 * out by hand, and refusals that leave the outputs alone. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "fake_hal.h"
#include "fw/limits.h"

#define STEP_HZ 100000u
#define SEGMENT_HZ 1000u

/* A controller booted on the defaults (empty storage) holds exactly what the function derives. */
static void test_defaults_match_controller(void **state)
{
    (void)state;
    static fake_hal f;
    static fw_controller c;
    fw_hal hal;
    fake_hal_init(&f, &hal);
    const fw_config cfg = {1, SEGMENT_HZ, STEP_HZ, false};
    assert_int_equal(fw_init(&c, &hal, &cfg), 0);

    fw_param_set s;
    fw_params_default(&s);
    tse_geometry g;
    fw_limits lim;
    assert_int_equal(fw_limits_from_params(&s, STEP_HZ, SEGMENT_HZ, &g, &lim), 0);
    assert_memory_equal(&g, &c.geom, sizeof g);
    assert_memory_equal(&lim, &c.lim, sizeof lim);
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

    /* A slower slide limit than the generator's binds instead: 50 mm/s. */
    s.v[FP_SLIDE_VMAX] = 50000;
    assert_int_equal(fw_limits_from_params(&s, STEP_HZ, SEGMENT_HZ, &g, &lim), 0);
    assert_true(fabs(lim.slide_vmax - 0.05) < 1e-12);
    /* A step rate limit of 20k/s: 5 ticks between steps, 98 / 5 = 19 steps a reversing segment
     * (0.9 * 19000 / 1.28M = 13.359375 mm/s), below the rate's own 0.9 * 20k / 1.28M = 14.0625. */
    s.v[FP_STEP_RATE_MAX] = 20000;
    assert_int_equal(fw_limits_from_params(&s, STEP_HZ, SEGMENT_HZ, &g, &lim), 0);
    assert_true(fabs(lim.slide_vmax - 0.013359375) < 1e-12);
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
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
