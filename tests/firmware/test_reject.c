/* What a REJECT names beyond its reason, over the wire: the state that refused, and for a timed
 * point too fast for the slides the slide, the limit and by how much (controller.h). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "fw/reject.h"
#include "harness.h"

#define MOVE_FN 0x0D
#define TRAJ_FN 0x0E

/* The slide speed limit the defaults give at 100 kHz steps and 1 kHz segments, by hand: a
 * reversing segment holds 100 - 2 ticks of DIR set-up = 98 steps, 98 kHz / 1.28M steps/m =
 * 76.5625 mm/s, of which planning uses 90 % (test_limits.c).  Below the 150 mm/s parameter: the
 * step generator's limit is the one in effect. */
#define SLIDE_VMAX 0.06890625

enum { REJ_FUNCTION, REJ_SEQ, REJ_REASON, REJ_SCISSOR, REJ_KIN, REJ_FIELD, REJ_WHERE };

static void expect_state_reject(unsigned from, uint8_t function, fw_state st)
{
    fw_poll(C);
    const proto_message r = reject_of(from, function);
    assert_int_equal(r.v[REJ_REASON], FW_REASON_STATE);
    assert_int_equal(r.v[REJ_FIELD], st);
    assert_int_equal(r.v[REJ_SCISSOR], 0);
    assert_int_equal(r.v[REJ_WHERE], 0);
}

/* HOME while homing: the host tool waits on this one, and learns it is homing. */
static void test_home_during_homing(void **state)
{
    (void)state;
    reach(FW_STATE_HOMING);
    const unsigned from = F.tx_count;
    cmd(PM_HOME);
    expect_state_reject(from, proto_table[PM_HOME].function, FW_STATE_HOMING);
}

static void test_move_while_disabled(void **state)
{
    (void)state;
    reach(FW_STATE_DISABLED);
    const unsigned from = F.tx_count;
    move_to(NEAR, 2000);
    expect_state_reject(from, MOVE_FN, FW_STATE_DISABLED);
}

/* Refusals past the table carry the state too: a trajectory point during a move, a move during a
 * trajectory, CLEAR_FAULT with the e-stop input still open. */
static void test_commit_and_clear_refusals(void **state)
{
    (void)state;
    reach(FW_STATE_MOVING);
    unsigned from = F.tx_count;
    traj_row(NEAR, 50000, true, false);
    expect_state_reject(from, TRAJ_FN, FW_STATE_MOVING);

    reach(FW_STATE_IDLE);
    const fw_inspection at = now();
    from = F.tx_count;
    traj_row(at.pose, 50000, true, false); /* a trajectory opens, held at rest while it fills */
    run(1);
    assert_int_equal(answer(from, TRAJ_FN, NULL), 'a');
    assert_int_equal(fw_state_of(C), FW_STATE_MOVING);
    from = F.tx_count;
    const double other[6] = {0.06, 0.06, 1.10, 0, 0, 0.05};
    move_to(other, 1500);
    expect_state_reject(from, MOVE_FN, FW_STATE_MOVING);

    reach(FW_STATE_IDLE);
    F.estop_open = true;
    fake_run(&F, C, 1);
    assert_int_equal(fw_state_of(C), FW_STATE_ESTOP);
    from = F.tx_count;
    cmd(PM_CLEAR_FAULT);
    expect_state_reject(from, proto_table[PM_CLEAR_FAULT].function, FW_STATE_ESTOP);
}

/* Which slide moves most between the rest pose and p, by the inverse kinematics of both (its
 * travel in *dq), required clearly ahead of the rest so that rounding cannot pick another. */
static int fastest_slide(const double p[6], double *dq)
{
    tse_ik_result a, b;
    assert_int_equal(tse_ik(fw_geometry_of(C), now().pose, NULL, &a), TSE_OK);
    assert_int_equal(tse_ik(fw_geometry_of(C), p, a.q, &b), TSE_OK);
    int best = 0;
    for (int k = 1; k < 6; ++k)
        if (fabs(b.q[k] - a.q[k]) > fabs(b.q[best] - a.q[best]))
            best = k;
    for (int k = 0; k < 6; ++k)
        if (k != best)
            assert_true(fabs(b.q[k] - a.q[k]) < 0.8 * fabs(b.q[best] - a.q[best]));
    *dq = fabs(b.q[best] - a.q[best]);
    return best;
}

/* A single point from rest, 50 ms away along Y and Z together (which drives B1 clearly fastest);
 * the reject it gets.  Nothing moves. */
static proto_message refused_point(double d, int *slide, double *dq)
{
    double p[6];
    memcpy(p, now().pose, sizeof p);
    p[1] += d;
    p[2] += d;
    *slide = fastest_slide(p, dq);
    const uint64_t pulses = F.pulses;
    const unsigned from = F.tx_count;
    traj_row(p, 50000, true, false);
    fw_poll(C);
    run(20);
    assert_int_equal(fw_state_of(C), FW_STATE_IDLE);
    assert_true(F.pulses == pulses);
    return reject_of(from, TRAJ_FN);
}

/* Too fast for the slide speed: with the acceleration limit at its 20 m/s^2 maximum, jumping to
 * speed v from rest measures v / 10 ms / 20 = 5 v against the limit, while the speed is v / 69 mm/s,
 * 14.5 v: the speed is the worse.  Expected: that slide's travel / 50 ms against `vmax`, to 2 %
 * (the path bends a little in slide space), the limit named as `limit`. */
static void timing_speed(int32_t slide_vmax_um, double vmax, fw_slide_limit limit)
{
    start();
    assert_int_equal(set_param(FP_SLIDE_AMAX, 20000000, NULL, NULL), 'a');
    assert_int_equal(set_param(FP_SLIDE_VMAX, slide_vmax_um, NULL, NULL), 'a');
    home();
    int k;
    double dq;
    const proto_message r = refused_point(0.004, &k, &dq);
    const double want = dq / 0.05 / vmax;
    assert_true(want > 1.2);
    assert_int_equal(r.v[REJ_REASON], FW_REASON_TIMING);
    assert_int_equal(r.v[REJ_FIELD], k + 1 + 16 * (int)limit);
    assert_int_equal(r.v[REJ_SCISSOR], k / 2 + 1);
    assert_int_equal(r.v[REJ_KIN], 0);
    if (fabs(r.v[REJ_WHERE] - 1000.0 * want) > 20.0 * want)
        fail_msg("where %d, by hand %.0f", r.v[REJ_WHERE], 1000.0 * want);
}

/* The defaults: the step generator's 68.9 mm/s binds, not slide_vmax's 150, and the frame says so
 * (field + 32) with the demand per mille of 68.9 mm/s. */
static void test_timing_speed(void **state)
{
    (void)state;
    timing_speed(150000, SLIDE_VMAX, FW_LIMIT_STEP_GENERATOR);
}

/* slide_vmax at 40 mm/s, below the step generator's 68.9: slide_vmax binds, named as such (field
 * + 0), the demand per mille of 40 mm/s. */
static void test_timing_speed_slide_vmax(void **state)
{
    (void)state;
    timing_speed(40000, 0.04, FW_LIMIT_SLIDE_VMAX);
}

/* Slow enough for the speed limit (a fifth of it) but reached at once from rest: the acceleration,
 * v / 10 ms (second differences over 10 segments, slide_check.h) against the 1 m/s^2 default. */
static void test_timing_acceleration(void **state)
{
    (void)state;
    reach(FW_STATE_IDLE);
    int k;
    double dq;
    const proto_message r = refused_point(0.0005, &k, &dq);
    const double v = dq / 0.05, want = v / 0.01 / 1.0;
    assert_true(v < 0.25 * SLIDE_VMAX && want > 1.2);
    assert_int_equal(r.v[REJ_REASON], FW_REASON_TIMING);
    assert_int_equal(r.v[REJ_FIELD], k + 1 + FW_REJECT_ACCEL);
    assert_int_equal(r.v[REJ_SCISSOR], k / 2 + 1);
    if (fabs(r.v[REJ_WHERE] - 1000.0 * want) > 20.0 * want)
        fail_msg("where %d, by hand %.0f", r.v[REJ_WHERE], 1000.0 * want);
}

/* Far beyond the limit the per mille stops at the field's 65535 rather than the frame being lost:
 * 20 mm in 1 ms from rest. */
static void test_timing_capped(void **state)
{
    (void)state;
    reach(FW_STATE_IDLE);
    double p[6];
    memcpy(p, now().pose, sizeof p);
    p[2] += 0.02;
    const unsigned from = F.tx_count;
    traj_row(p, 1000, true, false);
    fw_poll(C);
    const proto_message r = reject_of(from, TRAJ_FN);
    assert_int_equal(r.v[REJ_REASON], FW_REASON_TIMING);
    assert_int_equal(r.v[REJ_WHERE], 65535);
}

/* A PARAM_SET refused names the parameter set (field) and the rule the set breaks (where), each
 * case worked by hand at the harness's 100 kHz step interrupts (10 us) and 1 kHz segments; nothing
 * changes.  A case may first set another parameter (pre_id, -1 for none), undone after it. */
static void test_param_set_rules(void **state)
{
    (void)state;
    static const struct {
        int pre_id;
        int32_t pre_value;
        int id;
        int32_t value;
        fw_reason reason;
        fw_param_rule rule;
    } cases[] = {
        {-1, 0, FP_L, 0, FW_REASON_PARAM_RANGE, FW_RULE_NONE},                    /* below 0.1 m */
        {-1, 0, FP_ALPHA_MIN, 1300000, FW_REASON_PARAM_SET, FW_RULE_ALPHA_ORDER}, /* 1.3 > 1.215271 rad */
        {-1, 0, FP_S_MIN, 900000, FW_REASON_PARAM_SET, FW_RULE_STROKE_ORDER},     /* = s_max, 0.9 m */
        {-1, 0, FP_S_MAX, 150000, FW_REASON_PARAM_SET, FW_RULE_SWITCH_STROKE},    /* switches at 0.2 m */
        /* The alpha_max stop: a scissor at least 2 l0 cos(alpha_max) = 2 (0.2647) (1.727)
         * cos(1.215271) = 0.318243 m wide; with cos(2 eta) = 1/2 its width is
         * sqrt(a^2 + b^2 + a b): 0.1835 m and 0.2 m give 0.332, both at 0.1835 m 0.317831. */
        {FP_HOME_SW_1, 183500, FP_HOME_SW_2, 183500, FW_REASON_PARAM_SET, FW_RULE_SWITCH_REACH},
        {-1, 0, FP_STEP_PULSE_NS, 10000, FW_REASON_PARAM_SET, FW_RULE_PULSE_PERIOD}, /* a whole tick */
        {-1, 0, FP_STEP_PULSE_NS, 6000, FW_REASON_PARAM_SET, FW_RULE_PULSE_LOW},     /* 4 us low < 6 high */
        /* 1 ms: 100 ticks + 1, more than a segment's 100; 0.99 ms: 99 + 1, none left for a step. */
        {-1, 0, FP_DIR_SETUP_NS, 1000000, FW_REASON_PARAM_SET, FW_RULE_DIR_SETUP_ROOM},
        {-1, 0, FP_DIR_SETUP_NS, 990000, FW_REASON_PARAM_SET, FW_RULE_DIR_SETUP_ROOM},
    };
    reach(FW_STATE_DISABLED);
    const fw_param_set before = (*fw_params_of(C));
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        if (cases[i].pre_id >= 0)
            assert_int_equal(set_param(cases[i].pre_id, cases[i].pre_value, NULL, NULL), 'a');
        const unsigned from = F.tx_count;
        const int32_t set[2] = {cases[i].id, cases[i].value};
        send(PM_PARAM_SET, set);
        fw_poll(C);
        const proto_message r = reject_of(from, proto_table[PM_PARAM_SET].function);
        if (r.v[REJ_REASON] != (int32_t)cases[i].reason || r.v[REJ_WHERE] != (int32_t)cases[i].rule)
            fail_msg("case %zu: reason %d rule %d, by hand %d and %d", i, r.v[REJ_REASON], r.v[REJ_WHERE],
                     cases[i].reason, cases[i].rule);
        assert_int_equal(r.v[REJ_FIELD], cases[i].id);
        assert_int_equal(r.v[REJ_SCISSOR], 0);
        assert_int_equal(r.v[REJ_KIN], 0);
        if (cases[i].pre_id >= 0)
            assert_int_equal(set_param(cases[i].pre_id, before.v[cases[i].pre_id], NULL, NULL), 'a');
        assert_memory_equal(fw_params_of(C), &before, sizeof before);
    }
    /* The pulse rule broken by another parameter: at step_rate_max 50k/s a step comes at most every
     * 2 ticks (20 us), and a 6 us pulse leaves 14 us low; back at 200k/s, every tick (10 us), 4 us
     * low: refused, naming step_rate_max and the pulse's rule. */
    assert_int_equal(set_param(FP_STEP_RATE_MAX, 50000, NULL, NULL), 'a');
    assert_int_equal(set_param(FP_STEP_PULSE_NS, 6000, NULL, NULL), 'a');
    const unsigned from = F.tx_count;
    const int32_t set[2] = {FP_STEP_RATE_MAX, 200000};
    send(PM_PARAM_SET, set);
    fw_poll(C);
    const proto_message r = reject_of(from, proto_table[PM_PARAM_SET].function);
    assert_int_equal(r.v[REJ_REASON], FW_REASON_PARAM_SET);
    assert_int_equal(r.v[REJ_FIELD], FP_STEP_RATE_MAX);
    assert_int_equal(r.v[REJ_WHERE], FW_RULE_PULSE_LOW);
    assert_int_equal(fw_params_of(C)->v[FP_STEP_RATE_MAX], 50000);
    /* The longest of each that fits: a 5 us pulse leaves 5 us low; 0.98 ms of set-up is 98 + 1 ticks,
     * one left for a step. */
    assert_int_equal(set_param(FP_STEP_PULSE_NS, 5000, NULL, NULL), 'a');
    assert_int_equal(set_param(FP_STEP_RATE_MAX, 200000, NULL, NULL), 'a');
    assert_int_equal(set_param(FP_DIR_SETUP_NS, 980000, NULL, NULL), 'a');
}

/* The encoding alone, on results written out by hand. */
static void test_values(void **state)
{
    (void)state;
    int32_t v[PROTO_MAX_FIELDS];
    fw_plan_result why;
    fw_plan_clear(&why);
    why.reason = FW_REASON_TIMING;
    why.slide = 4; /* B2 */
    why.scissor = 2;
    why.ratio = 1.35;
    fw_reject_values(0x8E, 9, FW_REASON_TIMING, 0, &why, v);
    const int32_t speed[7] = {0x0E, 9, FW_REASON_TIMING, 2, 0, 4, 1350};
    assert_memory_equal(v, speed, sizeof speed);
    why.limit = FW_LIMIT_STEP_GENERATOR; /* the step generator's speed limit: + 2 x 16 */
    fw_reject_values(0x0E, 9, FW_REASON_TIMING, 0, &why, v);
    assert_int_equal(v[5], 4 + 32);
    assert_int_equal(v[6], 1350);
    why.accel = true;
    why.ratio = 1e6; /* a million times over: the field's top */
    fw_reject_values(0x0E, 9, FW_REASON_TIMING, 0, &why, v);
    assert_int_equal(v[5], 4 + 16); /* the acceleration, as ever */
    assert_int_equal(FW_REJECT_ACCEL, 16);
    assert_int_equal(v[6], 65535);
    why.ratio = NAN;
    fw_reject_values(0x0E, 9, FW_REASON_TIMING, 0, &why, v);
    assert_int_equal(v[6], 65535);

    fw_plan_clear(&why);
    why.reason = FW_REASON_KINEMATICS;
    why.scissor = 3;
    why.status = TSE_SINGULAR;
    why.where = 0.4567;
    fw_reject_values(0x0D, 7, FW_REASON_KINEMATICS, 0, &why, v);
    const int32_t kin[7] = {0x0D, 7, FW_REASON_KINEMATICS, 3, TSE_SINGULAR, 0, 457};
    assert_memory_equal(v, kin, sizeof kin);

    /* The other reasons carry the caller's field and nothing of a result. */
    fw_reject_values(0x08, 3, FW_REASON_STATE, FW_STATE_HOMING, &why, v);
    const int32_t st[7] = {0x08, 3, FW_REASON_STATE, 0, 0, FW_STATE_HOMING, 0};
    assert_memory_equal(v, st, sizeof st);
    fw_reject_values(0x10, 0, FW_REASON_PARAM_RANGE, FP_SLIDE_AMAX, NULL, v);
    const int32_t pr[7] = {0x10, 0, FW_REASON_PARAM_RANGE, 0, 0, FP_SLIDE_AMAX, 0};
    assert_memory_equal(v, pr, sizeof pr);

    /* A parameter's refusal: the id (255 past it), and for param_set the rule in where. */
    fw_reject_param_values(0x10, FW_REASON_PARAM_SET, FP_STEP_PULSE_NS, FW_RULE_PULSE_LOW, v);
    const int32_t ps[7] = {0x10, 0, FW_REASON_PARAM_SET, 0, 0, FP_STEP_PULSE_NS, 8};
    assert_memory_equal(v, ps, sizeof ps);
    fw_reject_param_values(0x10, FW_REASON_PARAM_RANGE, FP_L, FW_RULE_RANGE, v);
    const int32_t pl[7] = {0x10, 0, FW_REASON_PARAM_RANGE, 0, 0, FP_L, 0};
    assert_memory_equal(v, pl, sizeof pl);
    fw_reject_param_values(0x0F, FW_REASON_PARAM_UNKNOWN, 300, FW_RULE_NONE, v);
    const int32_t pu[7] = {0x0F, 0, FW_REASON_PARAM_UNKNOWN, 0, 0, 255, 0};
    assert_memory_equal(v, pu, sizeof pu);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_values),
        cmocka_unit_test(test_home_during_homing),
        cmocka_unit_test(test_move_while_disabled),
        cmocka_unit_test(test_commit_and_clear_refusals),
        cmocka_unit_test(test_timing_speed),
        cmocka_unit_test(test_timing_speed_slide_vmax),
        cmocka_unit_test(test_param_set_rules),
        cmocka_unit_test(test_timing_acceleration),
        cmocka_unit_test(test_timing_capped),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
