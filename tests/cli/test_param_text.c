/* Parameters as SI text (host_tools/params/param_text.h): every conversion family against values
 * worked by hand, the messages of refused values and sets, and the parameter file (round trips,
 * each error with its line, nothing half-applied, the file left alone on error). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmocka.h>

#include "param_text.h"
#include "kin_params_file.h"
#include "scratch_dir.h"

#define PI 3.14159265358979323846

static void put_file(const char *path, const char *bytes, size_t n)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(bytes, 1, n, f), n);
    assert_int_equal(fclose(f), 0);
}

/* The file's bytes (NUL-terminated; *n their count), for comparing before and after. */
static char *get_file(const char *path, size_t *n)
{
    static char buf[3][65536];
    static int which;
    char *b = buf[which++ % 3];
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    *n = fread(b, 1, sizeof buf[0] - 1, f);
    b[*n] = '\0';
    fclose(f);
    return b;
}

static void assert_contains(const char *s, const char *fragment)
{
    if (!strstr(s, fragment))
        fail_msg("'%s' does not contain '%s'", s, fragment);
}

static param_key key(const char *name)
{
    param_key k;
    if (param_lookup(name, &k) != 0)
        fail_msg("'%s' unknown", name);
    return k;
}

static int32_t from(const char *name, const char *text)
{
    const param_key k = key(name);
    int32_t raw = 0;
    char err[256] = "";
    if (param_from_text(&k, text, &raw, err, sizeof err) != 0)
        fail_msg("%s = '%s' refused: %s", name, text, err);
    return raw;
}

/* Refused, *raw untouched, and the message is exactly `want`. */
static void refused(const char *name, const char *text, const char *want)
{
    const param_key k = key(name);
    int32_t raw = 12345;
    char err[256] = "";
    if (param_from_text(&k, text, &raw, err, sizeof err) == 0)
        fail_msg("%s = '%s' accepted as %d", name, text, raw);
    assert_int_equal(raw, 12345);
    assert_string_equal(err, want);
}

static const char *to(const char *name, int32_t raw)
{
    static char buf[4][64];
    static int which;
    const param_key k = key(name);
    return param_to_text(&k, raw, buf[which++ % 4], sizeof buf[0]);
}

static void test_lookup(void **state)
{
    (void)state;
    param_key k;
    assert_int_equal(param_lookup("L", &k), 0);
    assert_int_equal(k.id, FP_L);
    assert_true(k.per_unit == 1e6);
    assert_string_equal(k.unit, "m");
    assert_int_equal(param_lookup("l", &k), 0); /* case does not matter */
    assert_int_equal(k.id, FP_L);
    assert_int_equal(param_lookup("Slide_VMAX", &k), 0);
    assert_int_equal(k.id, FP_SLIDE_VMAX);
    assert_string_equal(k.unit, "m/s");
    assert_int_equal(param_lookup("ETA_DEG", &k), 0);
    assert_int_equal(k.id, FP_ETA);
    assert_string_equal(k.unit, "deg");
    assert_true(fabs(k.per_unit - 1e6 * PI / 180.0) < 1e-9);
    assert_int_equal(param_lookup("alpha_min_deg", &k), 0);
    assert_int_equal(k.id, FP_ALPHA_MIN);
    assert_int_equal(param_lookup("alpha_max_deg", &k), 0);
    assert_int_equal(k.id, FP_ALPHA_MAX);
    assert_int_equal(param_lookup("k1", &k), 0);
    assert_string_equal(k.unit, "");
    assert_int_equal(param_lookup("watchdog_ms", &k), 0);
    assert_string_equal(k.unit, "ms");
    assert_true(k.per_unit == 1.0);
    assert_int_equal(param_lookup("can_kbps", &k), 0);
    assert_string_equal(k.unit, "kbit/s");

    k.id = 99;
    const char *unknown[] = {"foo", "", "_deg", "eta_degx", "eta_", "slide_vmax_deg", "plate_wmax_deg", "L_deg",
                             "watchdog", "alpha"};
    for (size_t i = 0; i < sizeof unknown / sizeof unknown[0]; ++i)
        if (param_lookup(unknown[i], &k) != -1)
            fail_msg("'%s' was found", unknown[i]);
    assert_int_equal(k.id, 99); /* untouched */

    /* Every table name finds its own parameter, and its SI spelling is that one. */
    for (int id = 0; id < FP_COUNT; ++id) {
        assert_int_equal(param_lookup(fw_param_table[id].name, &k), 0);
        assert_int_equal(k.id, id);
        param_key si;
        param_si_key(id, &si);
        assert_int_equal(si.id, id);
        assert_true(si.per_unit == k.per_unit);
        assert_string_equal(si.unit, k.unit);
    }
}

/* The SI units of every wire unit: micro-units are a million to one, the rest as written. */
static void test_si_units(void **state)
{
    (void)state;
    static const struct {
        int id;
        const char *unit;
        double per_unit;
    } want[] = {
        {FP_L, "m", 1e6},           {FP_K1, "", 1e6},
        {FP_ETA, "rad", 1e6},       {FP_SLIDE_VMAX, "m/s", 1e6},
        {FP_SLIDE_AMAX, "m/s^2", 1e6}, {FP_PLATE_JMAX, "m/s^3", 1e6},
        {FP_PLATE_WMAX, "rad/s", 1e6}, {FP_PLATE_DWMAX, "rad/s^2", 1e6},
        {FP_STEPS_PER_M, "1/m", 1},  {FP_STEP_RATE_MAX, "1/s", 1},
        {FP_WATCHDOG_MS, "ms", 1},   {FP_STEP_PULSE_NS, "ns", 1},
        {FP_CAN_KBPS, "kbit/s", 1},  {FP_HOME_SW_4, "m", 1e6},
    };
    for (size_t i = 0; i < sizeof want / sizeof want[0]; ++i) {
        param_key k;
        param_si_key(want[i].id, &k);
        assert_string_equal(k.unit, want[i].unit);
        assert_true(k.per_unit == want[i].per_unit);
    }
}

static void test_from_text(void **state)
{
    (void)state;
    assert_int_equal(from("slide_vmax", "0.2"), 200000);      /* m/s -> um/s */
    assert_int_equal(from("L", "1.727"), 1727000);            /* m -> um */
    assert_int_equal(from("eta_deg", "30"), 523599);          /* 30 pi/180 = 0.5235988 rad */
    assert_int_equal(from("eta_deg", "-30"), -523599);
    assert_int_equal(from("eta", "0.5"), 500000);             /* rad -> urad */
    assert_int_equal(from("alpha_max_deg", "60"), 1047198);   /* pi/3 = 1.0471976 rad */
    assert_int_equal(from("k1", "0.2647"), 264700);           /* ratio -> ppm */
    assert_int_equal(from("mu_min", "0.05"), 50000);
    assert_int_equal(from("slide_amax", "1.5"), 1500000);     /* m/s^2 */
    assert_int_equal(from("plate_jmax", "10"), 10000000);     /* m/s^3 */
    assert_int_equal(from("plate_wmax", "0.75"), 750000);     /* rad/s */
    assert_int_equal(from("plate_dwmax", "2"), 2000000);      /* rad/s^2 */
    assert_int_equal(from("steps_per_m", "1280000"), 1280000);/* 1/m as written */
    assert_int_equal(from("step_rate_max", "150000"), 150000);/* 1/s */
    assert_int_equal(from("watchdog_ms", "250"), 250);
    assert_int_equal(from("step_pulse_ns", "2500"), 2500);
    assert_int_equal(from("can_kbps", "250"), 250);
    assert_int_equal(from("home_sw_2", "2e-1"), 200000);
    assert_int_equal(from("slide_vmax", "  0.2\t"), 200000);  /* blanks around */
    /* To the nearest integer. */
    assert_int_equal(from("s_max", "0.9000004"), 900000);
    assert_int_equal(from("s_max", "0.9000006"), 900001);
    assert_int_equal(from("watchdog_ms", "2.5"), 3);           /* halves away from zero */
    assert_int_equal(from("watchdog_ms", "2.4"), 2);
    /* The bounds themselves. */
    assert_int_equal(from("slide_vmax", "0.001"), 1000);
    assert_int_equal(from("slide_vmax", "2"), 2000000);
    assert_int_equal(from("watchdog_ms", "0"), 0);
}

static void test_refused_values(void **state)
{
    (void)state;
    refused("slide_vmax", "3", "slide_vmax = 3 m/s is outside 0.001..2 m/s");
    refused("slide_vmax", "0.0004", "slide_vmax = 0.0004 m/s is outside 0.001..2 m/s");
    refused("k1", "2", "k1 = 2 is outside 0.000001..1");
    refused("k1", "0", "k1 = 0 is outside 0.000001..1");
    refused("L", "1e10", "L = 1e10 m is outside 0.1..10 m"); /* beyond int32 too */
    refused("watchdog_ms", "-1", "watchdog_ms = -1 ms is outside 0..60000 ms");
    refused("status_ms", "5", "status_ms = 5 ms is outside 10..10000 ms");
    /* In degrees, the range is shown in degrees: 1570796 urad is 89.999981 deg; "90" would come
     * back to it once rounded, but lies outside as written, so the ends are shown inside. */
    refused("eta_deg", "100", "eta = 100 deg is outside -89.99998..89.99998 deg");
    refused("eta_deg", "90", "eta = 90 deg is outside -89.99998..89.99998 deg");
    refused("k1", "1.0000004", "k1 = 1.0000004 is outside 0.000001..1"); /* 1 ppm once rounded */
    refused("L", "0.0999996", "L = 0.0999996 m is outside 0.1..10 m");
    refused("can_kbps", "300", "can_kbps = 300 kbit/s is not one of the rates 125, 250, 500, 1000 kbit/s");
    refused("can_kbps", "2000", "can_kbps = 2000 kbit/s is outside 125..1000 kbit/s");
    /* Not one finite number. */
    refused("slide_vmax", "fast", "slide_vmax: 'fast' is not one finite number (in m/s)");
    refused("slide_vmax", "0.2 m/s", "slide_vmax: '0.2 m/s' is not one finite number (in m/s)");
    refused("slide_vmax", "", "slide_vmax: '' is not one finite number (in m/s)");
    refused("slide_vmax", "0.1 0.2", "slide_vmax: '0.1 0.2' is not one finite number (in m/s)");
    refused("k1", "nan", "k1: 'nan' is not one finite number");
    refused("L", "inf", "L: 'inf' is not one finite number (in m)");
    refused("L", "1e999", "L: '1e999' is not one finite number (in m)");
    refused("eta_deg", "30deg", "eta: '30deg' is not one finite number (in deg)");
}

static void test_to_text(void **state)
{
    (void)state;
    assert_string_equal(to("slide_vmax", 150000), "0.15");
    assert_string_equal(to("L", 1727000), "1.727");
    assert_string_equal(to("L", 100000), "0.1");
    assert_string_equal(to("s_min", 0), "0");
    assert_string_equal(to("k1", 1), "0.000001");
    assert_string_equal(to("k1", 1000000), "1");
    assert_string_equal(to("eta", -1570796), "-1.570796");
    assert_string_equal(to("eta", -5), "-0.000005");
    assert_string_equal(to("plate_jmax", 500000000), "500");
    assert_string_equal(to("watchdog_ms", 500), "500");
    assert_string_equal(to("steps_per_m", 1280000), "1280000");
    /* 523599 urad is 30.0000127 deg, and 30 deg is 523598.8 urad: "30" is exact enough. */
    assert_string_equal(to("eta_deg", 523599), "30");
    /* 1 urad is 0.0000573 deg: five significant digits come back to it, fewer do not. */
    assert_string_equal(to("eta_deg", 1), "0.00006");
    /* Degrees of every raw value of an angle's range come back to that raw value. */
    const param_key k = key("alpha_min_deg");
    for (int32_t raw = 1; raw <= 1570796; raw += 997) {
        char t[64], err[256];
        int32_t back = -1;
        param_to_text(&k, raw, t, sizeof t);
        assert_int_equal(param_from_text(&k, t, &back, err, sizeof err), 0);
        assert_int_equal(back, raw);
    }
    /* A short buffer is cut, not overrun. */
    char small[4];
    const param_key l = key("L");
    assert_ptr_equal(param_to_text(&l, 1727000, small, sizeof small), small);
    assert_string_equal(small, "1.7");
}

static void explained(const fw_param_set *s, const char *want)
{
    char err[512] = "";
    param_explain_invalid(s, FW_RATES_BUILT_IN, err, sizeof err);
    assert_string_equal(err, want);
}

static void test_explain(void **state)
{
    (void)state;
    fw_param_set s;
    fw_params_default(&s);
    explained(&s, "the set is valid");

    s.v[FP_ALPHA_MIN] = 1300000;
    explained(&s, "alpha_min = 1.3 rad must be below alpha_max = 1.215271 rad");
    fw_params_default(&s);
    s.v[FP_S_MIN] = 950000;
    explained(&s, "s_min = 0.95 m must be below s_max = 0.9 m");
    fw_params_default(&s);
    s.v[FP_SLIDE_VMAX] = 3000000;
    explained(&s, "slide_vmax = 3 m/s is outside 0.001..2 m/s");
    fw_params_default(&s);
    s.v[FP_CAN_KBPS] = 300;
    explained(&s, "can_kbps = 300 kbit/s is not one of the rates 125, 250, 500, 1000 kbit/s");
    fw_params_default(&s);
    s.v[FP_HOME_SW_3] = 950000;
    explained(&s, "home_sw_3 = 0.95 m must be within the stroke s_min..s_max = 0..0.9 m");

    /* Slides 3 and 4 (scissor 2) at 0.05 m and 0.2 m: with cos(2 eta) = cos(60 deg) = 1/2 the
     * width is sqrt(0.05^2 + 0.2^2 + 0.05 * 0.2) = sqrt(0.0525) = 0.229129 m, below
     * 2 l0 cos(alpha_max) = 2 * 0.2647 * 1.727 * cos(1.215271) (about 0.318 m). */
    fw_params_default(&s);
    s.v[FP_HOME_SW_3] = 50000;
    char want[512], err[512];
    snprintf(want, sizeof want,
             "home_sw_3 = 0.05 m: the six homing switches cannot be reached together (slides 3 and 4 at "
             "home_sw_3 = 0.05 m and home_sw_4 = 0.2 m make scissor 2 0.229129 m wide, narrower than 2 l0 "
             "cos(alpha_max) = %.6g m: its alpha_max stop halts them before the switches)",
             2 * 0.2647 * 1.727 * cos(1.215271));
    param_explain_invalid(&s, FW_RATES_BUILT_IN, err, sizeof err);
    assert_string_equal(err, want);
    assert_true(fabs(2 * 0.2647 * 1.727 * cos(1.215271) - 0.318) < 0.001);
    /* The second of a pair is blamed through its pair's first, as the firmware does. */
    fw_params_default(&s);
    s.v[FP_HOME_SW_6] = 50000;
    param_explain_invalid(&s, FW_RATES_BUILT_IN, err, sizeof err);
    assert_contains(err, "home_sw_5 = 0.2 m: the six homing switches cannot be reached together");
    assert_contains(err, "scissor 3");
}

/* Each rule the controller's rates add, worded with the values that decide it (200 kHz step
 * interrupts: 5 us; 1 kHz segments: 200 ticks), and each rule named by a refusal: never "valid". */
static void test_explain_timing(void **state)
{
    (void)state;
    fw_param_set s;
    fw_params_default(&s);
    s.v[FP_STEP_PULSE_NS] = 6000;
    explained(&s, "step_pulse_ns = 6000 ns does not end within one step interrupt period, 5000 ns at 200 kHz: it "
                  "must be shorter (at most 4999 ns)");
    /* The case: 4 us high leaves 1 us low before a step one tick later. */
    s.v[FP_STEP_PULSE_NS] = 4000;
    explained(&s, "step_pulse_ns = 4000 ns leaves 1000 ns low before the same slide's next step, which may come "
                  "5000 ns later (1 step interrupt at 200 kHz for step_rate_max = 200000 1/s): the low time must "
                  "be at least as long as the pulse (at most 2500 ns)");
    /* A step every 3 ticks at 70k/s (200k / 70k = 2.86, rounded up): 15 us apart, room for the
     * longest pulse that ends within its tick. */
    s.v[FP_STEP_RATE_MAX] = 70000;
    s.v[FP_STEP_PULSE_NS] = 4999;
    explained(&s, "the set is valid");
    s.v[FP_STEP_RATE_MAX] = 200000;
    s.v[FP_STEP_PULSE_NS] = 2501;
    explained(&s, "step_pulse_ns = 2501 ns leaves 2499 ns low before the same slide's next step, which may come "
                  "5000 ns later (1 step interrupt at 200 kHz for step_rate_max = 200000 1/s): the low time must "
                  "be at least as long as the pulse (at most 2500 ns)");
    fw_params_default(&s);
    /* 0.995 ms is 199 ticks + 1 of the 200: none left for a step; 0.99 ms (198 + 1) the longest. */
    s.v[FP_DIR_SETUP_NS] = 995000;
    explained(&s, "dir_setup_ns = 995000 ns takes 200 step interrupts (rounded up, plus one) of the 200 in a "
                  "control segment, leaving no room for a step (1 interrupt apart for step_rate_max = 200000 1/s) "
                  "in a segment that changes direction (at most 990000 ns)");
    s.v[FP_DIR_SETUP_NS] = 990000;
    explained(&s, "the set is valid");

    /* A refusal's rule, whatever tsectl's own judgement: the rule is the controller's. */
    fw_params_default(&s);
    const fw_param_fault rest = {FP_SLIDE_VMAX, FW_RULE_NOT_AT_REST};
    char err[512];
    param_explain_fault(&s, rest, FW_RATES_BUILT_IN, err, sizeof err);
    assert_string_equal(err, "the slides were still moving when the set came: set it again at rest");
    const fw_param_fault config = {-1, FW_RULE_CONFIG};
    param_explain_fault(&s, config, FW_RATES_BUILT_IN, err, sizeof err);
    assert_string_equal(err, "the controller's rates (200000 Hz step interrupts, 1000 Hz control segments) cannot run it");
    /* From a controller that names no rule: its generic words. */
    const fw_param_fault none = {FP_L, FW_RULE_NONE};
    param_explain_fault(&s, none, FW_RATES_BUILT_IN, err, sizeof err);
    assert_string_equal(err, "the value is in range but the whole set it gives is not valid (geometry, stroke, homing "
                             "switches or step timing)");
    /* A switch pair broken by setting its second switch: the judge's blame, the pair's first. */
    s.v[FP_HOME_SW_1] = 183500;
    s.v[FP_HOME_SW_2] = 183500;
    const fw_param_fault reach = {FP_HOME_SW_2, FW_RULE_SWITCH_REACH};
    param_explain_fault(&s, reach, FW_RATES_BUILT_IN, err, sizeof err);
    assert_contains(err, "home_sw_1 = 0.1835 m: the six homing switches cannot be reached together (slides 1 and 2");
    /* Every rule, on a set the local judge finds valid: words, never "valid". */
    fw_params_default(&s);
    for (int r = 0; r <= FW_RULE_COUNT; ++r) {
        const fw_param_fault f = {FP_SLIDE_VMAX, (fw_param_rule)r};
        param_explain_fault(&s, f, FW_RATES_BUILT_IN, err, sizeof err);
        if (!err[0] || strstr(err, "valid") == err || strstr(err, "is valid"))
            fail_msg("rule %d: '%s'", r, err);
    }
}

/* The same rules for a controller at other rates (tse-sim --step-hz, a board whose INFO says so): a
 * file, an explanation and the speed limit are judged at them.  At 100 kHz step interrupts (10 us)
 * and 1 kHz segments: a 4 us pulse leaves 6 us low before a step one tick later (taken; at 200 kHz
 * it leaves 1 us: refused); 6 us leaves 4 us (refused, at most 10 / 2 = 5 us); a segment that
 * changes direction holds 100 ticks less 1 + 1 for a 5 us DIR set-up: 98 steps,
 * 0.9 x 98000 / 1.28M = 0.06890625 m/s. */
static void test_other_rates(void **state)
{
    (void)state;
    const fw_rates slow = {100000, 1000};
    const char *p = scratch_path("rates.params");
    const char *text = "step_pulse_ns = 4000\n";
    put_file(p, text, strlen(text));
    fw_param_set s;
    fw_params_default(&s);
    char err[512] = "";
    assert_int_equal(param_file_read(p, &s, FW_RATES_BUILT_IN, err, sizeof err), -1);
    assert_contains(err, "rates.params:1: step_pulse_ns = 4000 ns leaves 1000 ns low");
    assert_int_equal(s.v[FP_STEP_PULSE_NS], 2500); /* untouched */
    assert_int_equal(param_file_read(p, &s, slow, err, sizeof err), 0);
    assert_int_equal(s.v[FP_STEP_PULSE_NS], 4000);
    param_explain_invalid(&s, slow, err, sizeof err);
    assert_string_equal(err, "the set is valid");
    assert_int_equal(param_file_write(p, &s, FW_RATES_BUILT_IN, err, sizeof err), -1);
    assert_int_equal(param_file_write(p, &s, slow, err, sizeof err), 0);
    s.v[FP_STEP_PULSE_NS] = 6000;
    param_explain_invalid(&s, slow, err, sizeof err);
    assert_string_equal(err, "step_pulse_ns = 6000 ns leaves 4000 ns low before the same slide's next step, which "
                             "may come 10000 ns later (1 step interrupt at 100 kHz for step_rate_max = 200000 1/s): "
                             "the low time must be at least as long as the pulse (at most 5000 ns)");
    fw_params_default(&s);
    char b[512];
    assert_contains(param_speed_limit_words(&s, slow, b, sizeof b),
                    "in effect: 0.06891 m/s, set by the step generator: 0.9 x 98 steps per 1 ms control segment");
    assert_contains(b, "(100 step interrupts at 100 kHz, less 2 for the DIR set-up");
    assert_true(fabs(0.9 * 98000 / 1280000.0 - 0.06890625) < 1e-12);
}

/* The slide speed limit in effect, by hand: at 200 kHz a segment that changes direction has 200
 * ticks less 1 + 1 of DIR set-up for 5 us: 198 steps, 0.9 x 198000 / 1.28M = 0.13921875 m/s. */
static void test_speed_words(void **state)
{
    (void)state;
    fw_param_set s;
    fw_params_default(&s);
    char b[512];
    assert_string_equal(param_speed_limit_words(&s, FW_RATES_BUILT_IN, b, sizeof b),
                        "slide speed limit in effect: 0.1392 m/s, set by the step generator: 0.9 x 198 steps per 1 ms "
                        "control segment / steps_per_m = 1280000 1/m, 198 being the steps that fit in a segment that "
                        "changes direction (200 step interrupts at 200 kHz, less 2 for the DIR set-up of dir_setup_ns "
                        "= 5000 ns, one step every 1 for step_rate_max = 200000 1/s); slide_vmax = 0.15 m/s is higher");
    s.v[FP_SLIDE_VMAX] = 120000;
    assert_string_equal(param_speed_limit_words(&s, FW_RATES_BUILT_IN, b, sizeof b),
                        "slide speed limit in effect: 0.12 m/s, slide_vmax (the step generator would allow 0.1392 m/s)");
    /* 60k/s: a step every 4 ticks (200k / 60k = 3.33), (200 - 2) / 4 = 49 steps, 0.9 x 49000 / 1.28M. */
    s.v[FP_STEP_RATE_MAX] = 60000;
    assert_contains(param_speed_limit_words(&s, FW_RATES_BUILT_IN, b, sizeof b), "in effect: 0.03445 m/s, set by the step generator: 0.9 x 49 steps");
    assert_contains(b, "one step every 4 for step_rate_max = 60000 1/s");
    assert_true(fabs(0.9 * 49000 / 1280000.0 - 0.0344531) < 1e-6);
    for (int id = 0; id < FP_COUNT; ++id)
        assert_int_equal(param_sets_speed_limit(id), id == FP_SLIDE_VMAX || id == FP_STEPS_PER_M ||
                                                          id == FP_STEP_RATE_MAX || id == FP_DIR_SETUP_NS);
}

/* A valid set unlike the defaults in every family, to read files into. */
static void changed_set(fw_param_set *s)
{
    fw_params_default(s);
    s->v[FP_L] = 1800001;
    s->v[FP_K1] = 250001;
    s->v[FP_ETA] = 400003;
    s->v[FP_ALPHA_MIN] = 200007;
    s->v[FP_ALPHA_MAX] = 1200011;
    s->v[FP_S_MAX] = 850013;
    s->v[FP_SLIDE_VMAX] = 123457;
    s->v[FP_PLATE_JMAX] = 9999999;
    s->v[FP_PLATE_WMAX] = 400001;
    s->v[FP_WATCHDOG_MS] = 0;
    s->v[FP_STEP_PULSE_NS] = 2500;
    s->v[FP_CAN_KBPS] = 250;
    s->v[FP_HOME_SW_1] = 250001;
    s->v[FP_HOME_SW_6] = 300007;
    assert_int_equal(fw_params_check(s), -1);
}

static void test_file_round_trip(void **state)
{
    (void)state;
    const char *p = scratch_path("rt.params");
    char err[512] = "";
    fw_param_set def, s, changed;
    fw_params_default(&def);
    assert_int_equal(param_file_write(p, &def, FW_RATES_BUILT_IN, err, sizeof err), 0);
    changed_set(&s);
    assert_int_equal(param_file_read(p, &s, FW_RATES_BUILT_IN, err, sizeof err), 0);
    assert_memory_equal(&s, &def, sizeof s); /* every parameter is in the file */

    size_t n;
    const char *text = get_file(p, &n);
    assert_contains(text, "\nslide_vmax = 0.15\n");
    assert_contains(text, "\nL = 1.727\n");
    assert_contains(text, "\nwatchdog_ms = 500\n");
    assert_contains(text, "\n# slide speed limit\n# in m/s, 0.001..2, default 0.15\nslide_vmax = 0.15\n");
    assert_contains(text, "\n# in rad (or eta_deg in degrees), -1.570796..1.570796, default 0.523599\n");
    assert_contains(text, "\n# l0 / L\n# a ratio, 0.000001..1, default 0.2647\n");
    for (const char *line = text; *line; line = strchr(line, '\n') + 1) {
        const size_t len = strcspn(line, "\n");
        if (len > 100)
            fail_msg("line longer than 100: %.*s", (int)len, line);
    }
    assert_int_equal(access(scratch_path("rt.params.tmp"), F_OK), -1); /* nothing left behind */

    changed_set(&changed);
    assert_int_equal(param_file_write(p, &changed, FW_RATES_BUILT_IN, err, sizeof err), 0);
    fw_params_default(&s);
    assert_int_equal(param_file_read(p, &s, FW_RATES_BUILT_IN, err, sizeof err), 0);
    assert_memory_equal(&s, &changed, sizeof s);
    assert_contains(get_file(p, &n), "\nslide_vmax = 0.123457\n");
}

/* `tsectl params dump` of a set unlike the defaults reads back to the same set through tse-sim's
 * reader (param_file_read) and, for the kinematic keys, tse-kin's (kin_params_load, which tse.kin
 * uses too), each value within half a micro-unit of the wire integer; the units are comments. */
static void test_dump_round_trip(void **state)
{
    (void)state;
    fw_param_set c, back;
    changed_set(&c);
    const char *p = scratch_path("dump.params");
    FILE *f = fopen(p, "w");
    assert_non_null(f);
    param_file_dump(f, &c, FW_RATES_BUILT_IN, "parameters of node 1");
    assert_int_equal(fclose(f), 0);
    size_t n;
    const char *text = get_file(p, &n);
    assert_true(!strncmp(text, "# parameters of node 1\n# slide speed limit in effect: 0.123457 m/s, slide_vmax (the "
                               "step generator would allow 0.1392 m/s)\nL = 1.800001   # m\n", 142));
    assert_contains(text, "\nL = 1.800001   # m\n");
    assert_contains(text, "\nk1 = 0.250001   # ratio\n");
    assert_contains(text, "\nslide_vmax = 0.123457   # m/s\n");
    assert_contains(text, "\ncan_kbps = 250   # kbit/s\n");

    char err[512] = "";
    fw_params_default(&back);
    if (param_file_read(p, &back, FW_RATES_BUILT_IN, err, sizeof err) != 0)
        fail_msg("tse-sim's reader refused the dump: %s", err);
    assert_memory_equal(&back, &c, sizeof c);

    kin_param_values kv;
    kin_params_default(&kv);
    if (kin_params_load(p, KIN_PARAMS_CONTROLLER, &kv, err, sizeof err) != KIN_PARAMS_OK)
        fail_msg("tse-kin's reader refused the dump: %s", err);
    static const struct {
        tse_param_id kin;
        int fw;
    } pairs[] = {{TSE_PARAM_L, FP_L},         {TSE_PARAM_K1, FP_K1},       {TSE_PARAM_ETA, FP_ETA},
                 {TSE_PARAM_K3, FP_K3},       {TSE_PARAM_K4, FP_K4},       {TSE_PARAM_ALPHA_MIN, FP_ALPHA_MIN},
                 {TSE_PARAM_ALPHA_MAX, FP_ALPHA_MAX}, {TSE_PARAM_S_MIN, FP_S_MIN}, {TSE_PARAM_S_MAX, FP_S_MAX},
                 {TSE_PARAM_MU_MIN, FP_MU_MIN}, {TSE_PARAM_NU_MIN, FP_NU_MIN}};
    for (size_t i = 0; i < sizeof pairs / sizeof pairs[0]; ++i)
        if (fabs(kv.v[pairs[i].kin] * 1e6 - c.v[pairs[i].fw]) > 1e-6)
            fail_msg("%s: tse-kin read %.17g, the set has %d micro-units", fw_param_table[pairs[i].fw].name,
                     kv.v[pairs[i].kin], c.v[pairs[i].fw]);
}

/* Saving into a user's file keeps every line the user wrote and changes only values; what the
 * file does not set (and differs from the default) is appended; reading it back gives the set. */
static void saved_into(const char *before, size_t before_len, const fw_param_set *s, const char *want)
{
    char p[512];
    snprintf(p, sizeof p, "%s", scratch_path("user.params"));
    put_file(p, before, before_len);
    assert_int_equal(chmod(p, 0640), 0);
    char err[512] = "";
    if (param_file_write(p, s, FW_RATES_BUILT_IN, err, sizeof err) != 0)
        fail_msg("not written: %s", err);
    size_t n;
    const char *after = get_file(p, &n);
    assert_int_equal(n, strlen(want));
    assert_string_equal(after, want);
    struct stat st;
    assert_int_equal(stat(p, &st), 0);
    assert_int_equal(st.st_mode & 07777, 0640);
    assert_int_equal(access(scratch_path("user.params.tmp"), F_OK), -1);
    fw_param_set back;
    fw_params_default(&back);
    if (param_file_read(p, &back, FW_RATES_BUILT_IN, err, sizeof err) != 0)
        fail_msg("the saved file does not read: %s", err);
    assert_memory_equal(&back, s, sizeof back);
}

static void test_save_keeps_user_file(void **state)
{
    (void)state;
    fw_param_set s;
    fw_params_default(&s);
    s.v[FP_WATCHDOG_MS] = 250;
    s.v[FP_SLIDE_VMAX] = 120000;
    s.v[FP_ETA] = 436332; /* 25 deg: 25 pi / 180 = 0.4363323 rad */
    s.v[FP_PLATE_VMAX] = 250000;
    /* Comments, a blank line, a key in capitals in degrees, no blanks around '=', no last newline. */
    static const char mine[] = "# my robot, as built\n"
                               "L = 1.727   # as built\n"
                               "\n"
                               "ETA_DEG = 30   # thirty degrees\n"
                               "slide_vmax=0.14\n"
                               "watchdog_ms = 250 # slower host";
    saved_into(mine, sizeof mine - 1, &s,
               "# my robot, as built\n"
               "L = 1.727   # as built\n"
               "\n"
               "ETA_DEG = 25   # thirty degrees\n"
               "slide_vmax=0.12\n"
               "watchdog_ms = 250 # slower host\n"
               "\n"
               "# Saved by the controller (PARAM_SAVE): values this file did not set\n"
               "plate_vmax = 0.25   # m/s\n");
    /* A BOM and CRLF line ends stay, and what is appended ends its lines the same way. */
    fw_params_default(&s);
    s.v[FP_SLIDE_VMAX] = 140000;
    s.v[FP_CAN_KBPS] = 250;
    static const char crlf[] = "\xEF\xBB\xBF# mine\r\nslide_vmax = 0.140 \r\n";
    saved_into(crlf, sizeof crlf - 1, &s,
               "\xEF\xBB\xBF# mine\r\nslide_vmax = 0.140 \r\n\r\n"
               "# Saved by the controller (PARAM_SAVE): values this file did not set\r\n"
               "can_kbps = 250   # kbit/s\r\n");
    /* Nothing differs: the file comes back byte for byte (0.140 is 0.14: not rewritten). */
    static const char same[] = "# same\nslide_vmax = 0.140\ncan_kbps=250\n";
    saved_into(same, sizeof same - 1, &s, same);
    /* An empty file takes what differs from the defaults, under the comment alone. */
    saved_into("", 0, &s,
               "# Saved by the controller (PARAM_SAVE): values this file did not set\n"
               "slide_vmax = 0.14   # m/s\n"
               "can_kbps = 250   # kbit/s\n");

    /* A file that no longer reads is not written over. */
    char p[512];
    snprintf(p, sizeof p, "%s", scratch_path("user.params"));
    static const char broken[] = "# mine\nslide_vmax = fast\n";
    put_file(p, broken, sizeof broken - 1);
    char err[512] = "";
    assert_int_equal(param_file_write(p, &s, FW_RATES_BUILT_IN, err, sizeof err), -1);
    assert_contains(err, "which does not read as a parameter file now: ");
    assert_contains(err, "user.params:2: slide_vmax: 'fast' is not one finite number (in m/s)");
    size_t n;
    assert_string_equal(get_file(p, &n), broken);
    assert_int_equal(access(scratch_path("user.params.tmp"), F_OK), -1);
}

static void read_ok(const char *text, fw_param_set *s)
{
    const char *p = scratch_path("ok.params");
    put_file(p, text, strlen(text));
    char err[512] = "";
    fw_params_default(s);
    if (param_file_read(p, s, FW_RATES_BUILT_IN, err, sizeof err) != 0)
        fail_msg("refused: %s", err);
}

static void test_file_spellings(void **state)
{
    (void)state;
    fw_param_set s, want;
    /* BOM, CRLF, comments after values, blank lines, any case, degrees. */
    read_ok("\xEF\xBB\xBF# a comment\r\n\r\n  SLIDE_VMAX = 0.2   # faster\r\neta_deg=20\r\nCan_Kbps = 1000", &s);
    fw_params_default(&want);
    want.v[FP_SLIDE_VMAX] = 200000;
    want.v[FP_ETA] = 349066; /* 20 pi/180 = 0.34906585 rad */
    want.v[FP_CAN_KBPS] = 1000;
    assert_memory_equal(&s, &want, sizeof s);

    /* An empty file, or comments only: nothing changes. */
    read_ok("", &s);
    fw_params_default(&want);
    assert_memory_equal(&s, &want, sizeof s);
    read_ok("# nothing\n\n   \n", &s);
    assert_memory_equal(&s, &want, sizeof s);

    /* Missing keys keep the value the set had, not the default. */
    const char *p = scratch_path("keep.params");
    put_file(p, "L = 1.7\n", 8);
    changed_set(&s);
    changed_set(&want);
    want.v[FP_L] = 1700000;
    char err[512];
    assert_int_equal(param_file_read(p, &s, FW_RATES_BUILT_IN, err, sizeof err), 0);
    assert_memory_equal(&s, &want, sizeof s);
}

/* The file is refused with a message that is exactly `want_fmt` (%s standing for its path), or
 * begins with it when `prefix`, and the set is untouched. */
static void file_error_from(const fw_param_set *start, const char *text, size_t len, const char *want_fmt,
                            int prefix)
{
    const char *p = scratch_path("bad.params");
    put_file(p, text, len);
    fw_param_set s = *start;
    char err[512] = "", want[512];
    if (param_file_read(p, &s, FW_RATES_BUILT_IN, err, sizeof err) == 0)
        fail_msg("accepted: %s", text);
    snprintf(want, sizeof want, want_fmt, p);
    if (prefix) {
        if (strncmp(err, want, strlen(want)))
            fail_msg("'%s' does not begin with '%s'", err, want);
    } else {
        assert_string_equal(err, want);
    }
    assert_memory_equal(&s, start, sizeof s);
}

static void file_error(const char *text, size_t len, const char *want_fmt, int prefix)
{
    fw_param_set d;
    fw_params_default(&d);
    file_error_from(&d, text, len, want_fmt, prefix);
}
#define FILE_ERROR(text, want) file_error(text, sizeof text - 1, want, 0)
#define FILE_ERROR_BEGINS(text, want) file_error(text, sizeof text - 1, want, 1)

static void test_file_errors(void **state)
{
    (void)state;
    /* Each has a good line before the bad one: had it been applied, the set would differ. */
    FILE_ERROR("L = 1.7\n\nfoo = 1\n", "%s:3: unknown parameter 'foo'");
    FILE_ERROR("# c\neta_deg = 30\n\neta = 0.5\n", "%s:4: eta given twice (first on line 2 as eta_deg)");
    FILE_ERROR("L = 1.7\nl = 1.7\n", "%s:2: l given twice (first on line 1 as L)");
    FILE_ERROR("L = 1.7\nslide_vmax = fast\n", "%s:2: slide_vmax: 'fast' is not one finite number (in m/s)");
    FILE_ERROR("L = 1.7\nslide_vmax = 3 # too fast\n", "%s:2: slide_vmax = 3 m/s is outside 0.001..2 m/s");
    FILE_ERROR("L = 1.7\r\nL 1.7\r\n", "%s:2: expected 'name = value', got 'L 1.7'");
    FILE_ERROR("L = 1.7\n = 3\n", "%s:2: no parameter name before '='");
    FILE_ERROR("L = 1.7\nk1 =\n", "%s:2: k1: '' is not one finite number");
    FILE_ERROR("L = 1.7\ncan_kbps = 300\n",
               "%s:2: can_kbps = 300 kbit/s is not one of the rates 125, 250, 500, 1000 kbit/s");
    /* The whole set: the line of the key the firmware blames ... */
    FILE_ERROR("alpha_min = 1.3\nalpha_max = 1.2\n", "%s:2: alpha_min = 1.3 rad must be below alpha_max = 1.2 rad");
    FILE_ERROR("s_max = 0.5\nhome_sw_2 = 0.6\n", "%s:2: home_sw_2 = 0.6 m must be within the stroke s_min..s_max = 0..0.5 m");
    FILE_ERROR_BEGINS("# c\n\nhome_sw_3 = 0.05 # low\n",
                      "%s:3: home_sw_3 = 0.05 m: the six homing switches cannot be reached together");
    /* ... or, when the file does not set it, that its kept value is what is in conflict. */
    FILE_ERROR("alpha_min = 1.3\n", "%s: alpha_min = 1.3 rad must be below alpha_max = 1.215271 rad (alpha_max is "
                                    "not set in the file: its default is what is in conflict)");
    fw_param_set c;
    changed_set(&c);
    file_error_from(&c, "alpha_min = 1.3\n", strlen("alpha_min = 1.3\n"),
                    "%s: alpha_min = 1.3 rad must be below alpha_max = 1.200011 rad (alpha_max is not set in the "
                    "file: its value before reading is what is in conflict)",
                    0);

    /* Not a text file: the firmware's binary record, as the simulator used to write it. */
    uint8_t rec[256];
    fw_params_default(&c);
    const size_t n = fw_params_serialize(&c, rec, sizeof rec);
    assert_true(n > 0);
    file_error((const char *)rec, n, "%s: contains a NUL byte", 1);

    /* No file at all. */
    fw_param_set s = c;
    char err[512];
    assert_int_equal(param_file_read(scratch_path("absent.params"), &s, FW_RATES_BUILT_IN, err, sizeof err), -1);
    assert_contains(err, "absent.params: cannot open: No such file or directory");
    assert_memory_equal(&s, &c, sizeof s);
}

/* A write that cannot be done leaves the old file as it was, and no temporary behind. */
static void test_write_errors(void **state)
{
    (void)state;
    const char *p = scratch_path("keep.params");
    static const char old[] = "L = 1.7\n";
    put_file(p, old, sizeof old - 1);
    fw_param_set s;
    fw_params_default(&s);
    s.v[FP_ALPHA_MIN] = 1300000; /* a set the firmware refuses is not written */
    char err[512] = "";
    assert_int_equal(param_file_write(p, &s, FW_RATES_BUILT_IN, err, sizeof err), -1);
    assert_contains(err, "keep.params: not written: alpha_min = 1.3 rad must be below alpha_max = 1.215271 rad");
    size_t n;
    assert_string_equal(get_file(p, &n), old);
    assert_int_equal(access(scratch_path("keep.params.tmp"), F_OK), -1);

    /* The temporary cannot be made. */
    fw_params_default(&s);
    assert_int_equal(param_file_write(scratch_path("no/such/dir/p.params"), &s, FW_RATES_BUILT_IN, err, sizeof err), -1);
    assert_contains(err, "p.params.tmp: cannot create: No such file or directory");

    /* The rename cannot replace what is there (a directory): it stays, the temporary goes. */
    const char *d = scratch_path("adir");
    assert_int_equal(mkdir(d, 0700), 0);
    assert_int_equal(param_file_write(d, &s, FW_RATES_BUILT_IN, err, sizeof err), -1);
    assert_contains(err, "adir: cannot replace it with");
    struct stat st;
    assert_int_equal(stat(d, &st), 0);
    assert_true(S_ISDIR(st.st_mode));
    assert_int_equal(access(scratch_path("adir.tmp"), F_OK), -1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_lookup),        cmocka_unit_test(test_si_units),
        cmocka_unit_test(test_from_text),     cmocka_unit_test(test_refused_values),
        cmocka_unit_test(test_to_text),       cmocka_unit_test(test_explain),
        cmocka_unit_test(test_explain_timing), cmocka_unit_test(test_other_rates),
        cmocka_unit_test(test_speed_words),
        cmocka_unit_test(test_file_round_trip), cmocka_unit_test(test_file_spellings),
        cmocka_unit_test(test_dump_round_trip), cmocka_unit_test(test_save_keeps_user_file),
        cmocka_unit_test(test_file_errors),   cmocka_unit_test(test_write_errors),
    };
    return cmocka_run_group_tests(tests, scratch_dir_make, scratch_dir_remove);
}
