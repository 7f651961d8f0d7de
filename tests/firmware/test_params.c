/* Parameter table, checks and the storage record. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "fw/limits.h"
#include "fw/params.h"
#include "fw/types.h"
#include "tse/fk.h"

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

/* The firmware's ranges and defaults (fw_param_specs) and the host's table (fw_param_table), both
 * made from fw/params.def, agree; every parameter has its name, unit and documentation. */
static void test_specs_are_the_table(void **state)
{
    (void)state;
    for (int i = 0; i < FP_COUNT; ++i) {
        assert_int_equal(fw_param_specs[i].min, fw_param_table[i].min);
        assert_int_equal(fw_param_specs[i].max, fw_param_table[i].max);
        assert_int_equal(fw_param_specs[i].def, fw_param_table[i].def);
        assert_true(fw_param_table[i].name && fw_param_table[i].name[0]);
        assert_true(fw_param_table[i].unit && fw_param_table[i].unit[0]);
        assert_true(fw_param_table[i].doc && fw_param_table[i].doc[0]);
    }
}

static void test_set_one(void **state)
{
    (void)state;
    fw_param_set s, before;
    fw_params_default(&s);
    before = s;
    assert_int_equal(fw_params_set_one(&s, FP_COUNT, 1, NULL), FW_REASON_PARAM_UNKNOWN);
    assert_int_equal(fw_params_set_one(&s, FP_L, 0, NULL), FW_REASON_PARAM_RANGE);
    /* In range alone, invalid as a set: alpha_min above alpha_max. */
    assert_int_equal(fw_params_set_one(&s, FP_ALPHA_MIN, 1300000, NULL), FW_REASON_PARAM_SET);
    assert_int_equal(fw_params_set_one(&s, FP_S_MIN, 900000, NULL), FW_REASON_PARAM_SET);
    assert_memory_equal(&s, &before, sizeof s);
    assert_int_equal(fw_params_set_one(&s, FP_WATCHDOG_MS, 250, NULL), 0);
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
    assert_int_equal(FP_TRAJ_LEAD, FP_CAN_KBPS + 1);
    assert_int_equal(FP_NODE, FP_TRAJ_LEAD + 1);
    assert_int_equal(FP_ENABLE_LEVEL, FP_NODE + 1);
    assert_int_equal(FP_ENABLE_LEVEL, FP_COUNT - 1);
    assert_int_equal(s.v[FP_NODE], 1);         /* the node the board image was built for before */
    assert_int_equal(s.v[FP_ENABLE_LEVEL], 0); /* the board's own level */
    assert_int_equal(s.v[FP_TRAJ_LEAD], 200000); /* 0.2 s */
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
    assert_int_equal(fw_stepgen_config_from_params(&m, 200000, 1000, &sc), FW_RULE_PULSE_LOW);
    assert_int_equal(s.v[FP_CAN_KBPS], 500);
    before = s;
    /* CAN: four rates, anything else out of range, naming the parameter. */
    const int32_t rates[] = {125, 250, 500, 1000}, bad_rates[] = {124, 126, 300, 800, 999, 1001, 0};
    for (size_t i = 0; i < sizeof rates / sizeof rates[0]; ++i) {
        assert_int_equal(fw_params_set_one(&s, FP_CAN_KBPS, rates[i], NULL), 0);
        assert_int_equal(s.v[FP_CAN_KBPS], rates[i]);
    }
    for (size_t i = 0; i < sizeof bad_rates / sizeof bad_rates[0]; ++i) {
        assert_int_equal(fw_params_set_one(&s, FP_CAN_KBPS, bad_rates[i], NULL), FW_REASON_PARAM_RANGE);
        fw_param_set t = s;
        t.v[FP_CAN_KBPS] = bad_rates[i];
        assert_int_equal(fw_params_check(&t), FP_CAN_KBPS);
    }
    assert_int_equal(s.v[FP_CAN_KBPS], 1000);
    /* A switch outside the stroke [0, 0.9 m] is refused, naming it.  At its end, 0.9 m, with the
     * others at 0.2 m, it is in the stroke, but homing's final move from there leaves the
     * workspace. */
    fw_param_fault why;
    assert_int_equal(fw_params_set_one(&s, FP_HOME_SW_3, 900001, &why), FW_REASON_PARAM_SET);
    assert_int_equal(why.rule, FW_RULE_SWITCH_STROKE);
    assert_int_equal(fw_params_set_one(&s, FP_HOME_SW_3, 900000, &why), FW_REASON_PARAM_SET);
    assert_int_equal(why.rule, FW_RULE_HOMING_PATH);
    assert_int_equal(why.id, FP_HOME_SW_3);
    fw_param_set t = s;
    t.v[FP_HOME_SW_5] = 950000;
    assert_int_equal(fw_params_check(&t), FP_HOME_SW_5);
    /* The switches reachable together.  Prototype: l0 = 0.2647 * 1.727 = 0.45714 m, alpha_max =
     * asin(1.619 / 1.727), cos alpha_max = sqrt(1 - 0.937464^2) = 0.348083, so a scissor's width
     * must stay >= 2 l0 cos alpha_max = 0.318243 m; with eta = 30 deg, w = sqrt(sA^2 + sB^2 +
     * sA sB): both slides at 0.1835 m give 0.317831 (too narrow), at 0.1840 m 0.318697. */
    s = before;
    assert_int_equal(fw_params_set_one(&s, FP_HOME_SW_1, 183500, NULL), 0); /* with B at 0.2: 0.332 */
    assert_int_equal(fw_params_set_one(&s, FP_HOME_SW_2, 183500, NULL), FW_REASON_PARAM_SET);
    t = s;
    t.v[FP_HOME_SW_2] = 183500;
    assert_int_equal(fw_params_check(&t), FP_HOME_SW_1);
    assert_int_equal(fw_params_set_one(&s, FP_HOME_SW_2, 184000, NULL), 0);
    /* Per scissor, not per slide: 0.1 m and 0.3 m give sqrt(0.13) = 0.3606. */
    assert_int_equal(fw_params_set_one(&s, FP_HOME_SW_4, 300000, NULL), 0);
    assert_int_equal(fw_params_set_one(&s, FP_HOME_SW_3, 100000, NULL), 0);
    /* The timing parameters' own ranges (what fits the step interrupt is the controller's check). */
    assert_int_equal(fw_params_set_one(&s, FP_STEP_PULSE_NS, 99, NULL), FW_REASON_PARAM_RANGE);
    assert_int_equal(fw_params_set_one(&s, FP_DIR_SETUP_NS, -1, NULL), FW_REASON_PARAM_RANGE);
    assert_int_equal(fw_params_set_one(&s, FP_DIR_SETUP_NS, 0, NULL), 0);
}

/* Each rule of a set, with the parameter fw_params_judge blames, worked by hand on the defaults
 * (kinematics.md's prototype; the switch widths as in test_board_parameters); fw_params_set_one
 * says the same rule of the change that breaks it. */
static void test_judge_rules(void **state)
{
    (void)state;
    static const struct {
        int id, id2;      /* id2: a second change (-1: none) */
        int32_t value, value2;
        fw_param_rule rule;
        int blamed;
    } cases[] = {
        {FP_L, -1, 99999, 0, FW_RULE_RANGE, FP_L},                    /* below 0.1 m */
        {FP_CAN_KBPS, -1, 300, 0, FW_RULE_RANGE, FP_CAN_KBPS},        /* not one of the rates */
        {FP_ALPHA_MIN, -1, 1300000, 0, FW_RULE_ALPHA_ORDER, FP_ALPHA_MAX},
        {FP_ALPHA_MAX, -1, 188727, 0, FW_RULE_ALPHA_ORDER, FP_ALPHA_MAX}, /* equal stops */
        {FP_S_MIN, -1, 900000, 0, FW_RULE_STROKE_ORDER, FP_S_MAX},
        {FP_S_MAX, -1, 199999, 0, FW_RULE_SWITCH_STROKE, FP_HOME_SW_1}, /* every switch at 0.2 m */
        {FP_HOME_SW_4, -1, 900001, 0, FW_RULE_SWITCH_STROKE, FP_HOME_SW_4},
        {FP_HOME_SW_1, FP_HOME_SW_2, 183500, 183500, FW_RULE_SWITCH_REACH, FP_HOME_SW_1},
        {FP_HOME_SW_6, -1, 50000, 0, FW_RULE_SWITCH_REACH, FP_HOME_SW_5}, /* a pair through its first */
        {FP_HOME_SW_1, FP_HOME_SW_2, 184000, 184000, FW_RULE_NONE, -1},  /* 0.318697 m: wide enough */
        /* Home has nu 0.73 (issue 24): a margin of 0.9 leaves it no pose to move from. */
        {FP_NU_MIN, -1, 900000, 0, FW_RULE_HOME_MARGINS, FP_NU_MIN},
        /* Issue 24: from 12.8 % of the way from these switches (the others at 0.2 m) to home, nu
         * falls to 0.0015, then the slides have no pose. */
        {FP_HOME_SW_1, -1, 475000, 0, FW_RULE_HOMING_PATH, FP_HOME_SW_1},
        /* A plate one step turns by more than 1 mrad (the controller fuzzing's k4 = 1 ppm, a plate of
         * 1.7 um): r_top x steps_per_m = k4 1e-6 x 1.727 m x 1,280,000 / m at least 1000 is k4 at
         * least 452.4 ppm; with the default plate, steps_per_m at least 4,921.7. */
        {FP_K4, -1, 452, 0, FW_RULE_PLATE_STEP, FP_K4},
        {FP_K4, -1, 453, 0, FW_RULE_NONE, -1},
        {FP_STEPS_PER_M, -1, 4921, 0, FW_RULE_PLATE_STEP, FP_K4},
        {FP_STEPS_PER_M, -1, 4922, 0, FW_RULE_NONE, -1},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        fw_param_set s;
        fw_params_default(&s);
        s.v[cases[i].id] = cases[i].value;
        if (cases[i].id2 >= 0)
            s.v[cases[i].id2] = cases[i].value2;
        const fw_param_fault f = fw_params_judge(&s);
        if (f.rule != cases[i].rule || f.id != cases[i].blamed)
            fail_msg("case %zu: rule %d on %d, by hand %d on %d", i, f.rule, f.id, cases[i].rule, cases[i].blamed);
        assert_int_equal(fw_params_check(&s), cases[i].blamed);
        /* The last change, made on its own: refused with the same rule (a range, for a value out of
         * its own), nothing changed. */
        fw_params_default(&s);
        if (cases[i].id2 >= 0)
            s.v[cases[i].id] = cases[i].value;
        const fw_param_set before = s;
        const int id = cases[i].id2 >= 0 ? cases[i].id2 : cases[i].id;
        const int32_t value = cases[i].id2 >= 0 ? cases[i].value2 : cases[i].value;
        fw_param_fault why = {-2, FW_RULE_COUNT};
        const int r = fw_params_set_one(&s, (uint16_t)id, value, &why);
        if (cases[i].rule == FW_RULE_NONE) {
            assert_int_equal(r, 0);
            assert_int_equal(why.rule, FW_RULE_NONE);
            continue;
        }
        assert_int_equal(r, cases[i].rule == FW_RULE_RANGE ? FW_REASON_PARAM_RANGE : FW_REASON_PARAM_SET);
        assert_int_equal(why.rule, cases[i].rule);
        assert_memory_equal(&s, &before, sizeof s);
    }
}

/* Homing's final move from random switch sets (each switch 0.2 m to 0.2 m + spread, the issue's
 * spreads), walked independently of the judge at 960 points (ten between each two of its own) by
 * forward kinematics from the home end: a set whose walk leaves the valid poses is refused
 * (homing_path), and one the judge takes walks through valid poses only. */
static void test_homing_path_random(void **state)
{
    (void)state;
    uint64_t rng = 0x9E3779B97F4A7C15ull;
    static const int32_t spreads[] = {200000, 250000};
    int refused = 0, taken = 0;
    for (size_t sp = 0; sp < 2; ++sp)
        for (int n = 0; n < 200; ++n) {
            fw_param_set s;
            fw_params_default(&s);
            for (int k = 0; k < 6; ++k) {
                rng = rng * 6364136223846793005ull + 1442695040888963407ull;
                s.v[FP_HOME_SW_1 + k] = 200000 + (int32_t)((rng >> 33) % (uint64_t)(spreads[sp] + 1));
            }
            const fw_param_fault f = fw_params_judge(&s);
            if (f.rule != FW_RULE_NONE && f.rule != FW_RULE_HOMING_PATH)
                continue; /* another rule (the switches' reach) decides */
            tse_params p;
            fw_params_kinematics(&s, &p);
            tse_geometry g;
            assert_int_equal(tse_geometry_init(&g, &p), TSE_PARAM_OK);
            double seed[6];
            for (int k = 0; k < 6; ++k)
                seed[k] = g.home_pose[k];
            bool valid = true;
            for (int i = 960; i >= 0 && valid; --i) {
                double q[6];
                for (int k = 0; k < 6; ++k) {
                    const double from = s.v[FP_HOME_SW_1 + k] * 1e-6;
                    q[k] = from + (i / 960.0) * (g.home_s - from);
                }
                tse_fk_result r;
                valid = tse_fk(&g, q, seed, &r) == TSE_OK;
                for (int k = 0; k < 6; ++k)
                    seed[k] = r.pose[k];
            }
            if (f.rule == FW_RULE_HOMING_PATH) {
                ++refused;
                if (valid)
                    fail_msg("spread %d, set %d: refused, but its path walks through valid poses", spreads[sp], n);
            } else {
                ++taken;
                if (!valid)
                    fail_msg("spread %d, set %d: taken, but its path leaves the valid poses", spreads[sp], n);
            }
        }
    printf("homing paths: %d sets refused, %d taken\n", refused, taken);
    assert_true(refused >= 10);
    assert_true(taken >= 100);
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

/* CRC-32 of IEEE 802.3 (reflected, polynomial 0xEDB88320), written out here: the record's check. */
static uint32_t crc32_ieee(const uint8_t *p, size_t n)
{
    uint32_t c = 0xFFFFFFFFu;
    for (size_t i = 0; i < n; ++i)
        for (int k = 0; k < 8; ++k) {
            const uint32_t bit = (c ^ (p[i] >> k)) & 1u;
            c = (c >> 1) ^ (bit ? 0xEDB88320u : 0u);
        }
    return ~c;
}

/* A record written by a firmware that knew one parameter fewer (traj_lead appended since), laid
 * out by hand: "PEST", the count, a zero byte, the values, the CRC.  It is read, and traj_lead
 * takes its default; a count above this firmware's is refused. */
static void test_older_record(void **state)
{
    (void)state;
    fw_param_set s, back;
    fw_params_default(&s);
    s.v[FP_SLIDE_VMAX] = 120000;
    const unsigned n = FP_TRAJ_LEAD; /* ids 0 .. traj_lead - 1 */
    uint8_t buf[256];
    size_t len = 0;
    const uint8_t head[6] = {'P', 'E', 'S', 'T', (uint8_t)n, 0};
    memcpy(buf, head, sizeof head);
    len = sizeof head;
    for (unsigned i = 0; i < n; ++i, len += 4)
        for (int k = 0; k < 4; ++k)
            buf[len + (size_t)k] = (uint8_t)((uint32_t)s.v[i] >> (8 * k));
    const uint32_t crc = crc32_ieee(buf, len);
    for (int k = 0; k < 4; ++k)
        buf[len++] = (uint8_t)(crc >> (8 * k));
    fw_params_default(&back);
    back.v[FP_TRAJ_LEAD] = 5; /* to see it replaced by the default */
    back.v[FP_NODE] = 7;      /* (and node, enable_level, appended after it) */
    back.v[FP_ENABLE_LEVEL] = 2;
    assert_int_equal(fw_params_deserialize(&back, buf, len), 0);
    assert_int_equal(back.v[FP_SLIDE_VMAX], 120000);
    assert_int_equal(back.v[FP_TRAJ_LEAD], fw_param_table[FP_TRAJ_LEAD].def);
    assert_int_equal(back.v[FP_NODE], 1);
    assert_int_equal(back.v[FP_ENABLE_LEVEL], 0);
    /* A count this firmware does not know (a newer one's record): refused, nothing changed. */
    buf[4] = (uint8_t)(FP_COUNT + 1);
    const fw_param_set before = back;
    assert_int_equal(fw_params_deserialize(&back, buf, len), -1);
    assert_memory_equal(&back, &before, sizeof back);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_defaults_are_the_prototype),
        cmocka_unit_test(test_specs_are_the_table),
        cmocka_unit_test(test_set_one),
        cmocka_unit_test(test_board_parameters),
        cmocka_unit_test(test_judge_rules),
        cmocka_unit_test(test_homing_path_random),
        cmocka_unit_test(test_record),
        cmocka_unit_test(test_older_record),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
