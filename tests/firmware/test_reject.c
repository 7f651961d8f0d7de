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
 * 76.5625 mm/s, of which planning uses 90 % (test_limits.c).  Below the 150 mm/s parameter. */
#define SLIDE_VMAX 0.06890625

enum { REJ_FUNCTION, REJ_SEQ, REJ_REASON, REJ_SCISSOR, REJ_KIN, REJ_FIELD, REJ_WHERE };

static void expect_state_reject(unsigned from, uint8_t function, fw_state st)
{
    fw_poll(&C);
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

/* Refusals past the table carry the state too: a move during another on a no-blend board, a
 * trajectory point during a move, CLEAR_FAULT with the e-stop input still open. */
static void test_commit_and_clear_refusals(void **state)
{
    (void)state;
    reach(FW_STATE_MOVING);
    C.cfg.no_blend = true;
    unsigned from = F.tx_count;
    const double other[6] = {0.06, 0.06, 1.10, 0, 0, 0.05};
    move_to(other, 1500);
    expect_state_reject(from, MOVE_FN, FW_STATE_MOVING);

    from = F.tx_count;
    traj_row(NEAR, 50000, true, false);
    expect_state_reject(from, TRAJ_FN, FW_STATE_MOVING);

    reach(FW_STATE_IDLE);
    F.estop_open = true;
    fake_run(&F, &C, 1);
    assert_int_equal(C.state, FW_STATE_ESTOP);
    from = F.tx_count;
    cmd(PM_CLEAR_FAULT);
    expect_state_reject(from, proto_table[PM_CLEAR_FAULT].function, FW_STATE_ESTOP);
}

/* Which slide moves most between the rest pose and p, by the inverse kinematics of both (its
 * travel in *dq), required clearly ahead of the rest so that rounding cannot pick another. */
static int fastest_slide(const double p[6], double *dq)
{
    tse_ik_result a, b;
    assert_int_equal(tse_ik(&C.geom, C.pose, NULL, &a), TSE_OK);
    assert_int_equal(tse_ik(&C.geom, p, a.q, &b), TSE_OK);
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
    memcpy(p, C.pose, sizeof p);
    p[1] += d;
    p[2] += d;
    *slide = fastest_slide(p, dq);
    const uint64_t pulses = F.pulses;
    const unsigned from = F.tx_count;
    traj_row(p, 50000, true, false);
    fw_poll(&C);
    run(20);
    assert_int_equal(C.state, FW_STATE_IDLE);
    assert_true(F.pulses == pulses);
    return reject_of(from, TRAJ_FN);
}

/* Too fast for the slide speed: with the acceleration limit at its 20 m/s^2 maximum, jumping to
 * speed v from rest measures v / 10 ms / 20 = 5 v against the limit, while the speed is v / 69 mm/s,
 * 14.5 v: the speed is the worse.  Expected: that slide's travel / 50 ms against SLIDE_VMAX, to
 * 2 % (the path bends a little in slide space). */
static void test_timing_speed(void **state)
{
    (void)state;
    start();
    unsigned from = F.tx_count;
    const int32_t set[2] = {FP_SLIDE_AMAX, 20000000};
    send(PM_PARAM_SET, set);
    fw_poll(&C);
    assert_int_equal(answer(from, proto_table[PM_PARAM_SET].function, NULL), 'a');
    home();
    int k;
    double dq;
    const proto_message r = refused_point(0.004, &k, &dq);
    const double want = dq / 0.05 / SLIDE_VMAX;
    assert_true(want > 1.2);
    assert_int_equal(r.v[REJ_REASON], FW_REASON_TIMING);
    assert_int_equal(r.v[REJ_FIELD], k + 1);
    assert_int_equal(r.v[REJ_SCISSOR], k / 2 + 1);
    assert_int_equal(r.v[REJ_KIN], 0);
    if (fabs(r.v[REJ_WHERE] - 1000.0 * want) > 20.0 * want)
        fail_msg("where %d, by hand %.0f", r.v[REJ_WHERE], 1000.0 * want);
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
    memcpy(p, C.pose, sizeof p);
    p[2] += 0.02;
    const unsigned from = F.tx_count;
    traj_row(p, 1000, true, false);
    fw_poll(&C);
    const proto_message r = reject_of(from, TRAJ_FN);
    assert_int_equal(r.v[REJ_REASON], FW_REASON_TIMING);
    assert_int_equal(r.v[REJ_WHERE], 65535);
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
    why.accel = true;
    why.ratio = 1e6; /* a million times over: the field's top */
    fw_reject_values(0x0E, 9, FW_REASON_TIMING, 0, &why, v);
    assert_int_equal(v[5], 4 + FW_REJECT_ACCEL);
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
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_values),
        cmocka_unit_test(test_home_during_homing),
        cmocka_unit_test(test_move_while_disabled),
        cmocka_unit_test(test_commit_and_clear_refusals),
        cmocka_unit_test(test_timing_speed),
        cmocka_unit_test(test_timing_acceleration),
        cmocka_unit_test(test_timing_capped),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
