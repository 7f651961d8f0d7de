/* What the controller fuzz target (tests/fuzz/controller) found, as regression tests; each input
 * it found is kept in tests/fuzz/controller/regressions/ and replayed by replay_controller.
 * 1. A REJECT for a field out of range carried sequence number 0 instead of the frame's, so a host
 *    matching answers by it (tsectl) never saw the refusal.
 * 2. A step_rate_max that leaves a segment reversing a slide no room for one step gave the slides
 *    a speed limit of zero, and the set was taken.
 * 3. Homing ran at homing_speed whatever the slide speed limit and the step generator allowed:
 *    above them it overran the generator (a step overrun fault) instead of homing.
 * 4. A trajectory whose last point was queued, stopped before its end (STOP, or a fault's stop),
 *    jumped to that last point in the stop ramp's final segment: the slides ran the rest of the
 *    trajectory at full step rate, and the generator overran.
 * 5. A TRAJ_COMMIT refused because the trajectory takes no more points (after its last, or
 *    stopped) spent its number and dropped the staged pose, as a refusal for its content does:
 *    a refusal for the state must change nothing.
 * 6. A pose part newer than the pose being staged but not newer than the last commit was refused
 *    as stale, after it had already dropped the staged parts. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "harness.h"

/* The controller's answer to a raw frame, polled at once: its REJECT decoded (fails if none). */
static proto_message reject_raw(uint16_t id, uint8_t len, const uint8_t *data)
{
    const unsigned from = F.tx_count;
    fake_send(&F, id, len, data);
    fw_poll(C);
    return reject_of(from, (uint8_t)(id >> 4));
}

static void range_reject_carries_the_seq(void **state)
{
    (void)state;
    start();
    /* MOVE_COMMIT seq 9, kind 7 (0 or 1 only). */
    proto_message r = reject_raw(0x0D1, 6, (const uint8_t[]){9, 7, 0xE8, 3, 0, 0});
    assert_int_equal(r.v[2], FW_REASON_RANGE);
    assert_int_equal(r.v[5], 1); /* the field: kind */
    assert_int_equal(r.v[1], 9);
    /* POSE_A seq 200, x = 8.4 m (4 m at most). */
    r = reject_raw(0x0A1, 7, (const uint8_t[]){200, 0xFF, 0xFF, 0x7F, 0, 0, 0});
    assert_int_equal(r.v[2], FW_REASON_RANGE);
    assert_int_equal(r.v[1], 200);
    /* TRAJ_COMMIT seq 3, dt 0 (1 ms at least). */
    r = reject_raw(0x0E1, 7, (const uint8_t[]){3, 0, 0, 0, 0, 0, 3});
    assert_int_equal(r.v[2], FW_REASON_RANGE);
    assert_int_equal(r.v[1], 3);
    /* Frames without a sequence number, or whose length already refuses them: 0. */
    r = reject_raw(0x111, 4, (const uint8_t[]){1, 2, 3, 4}); /* PARAM_SAVE, wrong magic */
    assert_int_equal(r.v[2], FW_REASON_RANGE);
    assert_int_equal(r.v[1], 0);
    r = reject_raw(0x061, 2, (const uint8_t[]){5, 6}); /* ENABLE of two bytes */
    assert_int_equal(r.v[2], FW_REASON_BAD_LENGTH);
    assert_int_equal(r.v[1], 0);
}

static void step_rate_leaving_no_step_is_refused(void **state)
{
    (void)state;
    start();
    /* 100 kHz step interrupts, 1 ms segments: 100 ticks a segment, of which a segment that reverses
     * a slide keeps its DIR quiet for 2 (5 us of set-up: one tick, plus one).  At 1000 steps/s a
     * slide steps at most every 100 ticks: no step fits in the 98 left, the slide could not move. */
    uint8_t reason = 0;
    assert_int_equal(set_param(FP_STEP_RATE_MAX, 1000, &reason, NULL), 'r');
    assert_int_equal(reason, FW_REASON_PARAM_SET);
    assert_int_equal(fw_params_of(C)->v[FP_STEP_RATE_MAX], fw_param_table[FP_STEP_RATE_MAX].def);
    /* At 1100 steps/s, every 91 ticks: one step fits. */
    assert_int_equal(set_param(FP_STEP_RATE_MAX, 1100, &reason, NULL), 'a');
    assert_true(fw_limits_of(C)->slide_vmax > 0.0);
    /* The limit a controller adopts is never zero, whatever set it took. */
    for (int32_t rate = 1000; rate <= 3000; rate += 7) {
        const char a = set_param(FP_STEP_RATE_MAX, rate, &reason, NULL);
        assert_true(a == 'a' || a == 'r');
        assert_true(fw_limits_of(C)->slide_vmax > 0.0);
    }
}

static void homing_speed_held_to_the_slide_limit(void **state)
{
    (void)state;
    start();
    /* 20 mm above the switches: room to reach any speed the slide limit allows on the way down. */
    for (int k = 0; k < 6; ++k)
        F.steps[k] = FAKE_SWITCH_AT + 25600 + 100 * k;
    /* 0.5 m/s: 640 steps a millisecond at 1.28M steps/m, where the slides may go 150 mm/s (192)
     * and the step generator can give 100 a millisecond. */
    uint8_t reason = 0;
    assert_int_equal(set_param(FP_HOMING_SPEED, 500000, &reason, NULL), 'a');
    cmd(PM_ENABLE);
    run(5);
    cmd(PM_HOME);
    fw_poll(C);
    assert_int_equal(fw_state_of(C), FW_STATE_HOMING);
    int32_t was[6];
    memcpy(was, F.steps, sizeof was);
    int32_t fastest = 0;
    for (int ms = 0; ms < 20000 && fw_state_of(C) == FW_STATE_HOMING; ++ms) {
        if (ms % 10 == 0)
            heartbeat();
        fake_run(&F, C, 1);
        for (int k = 0; k < 6; ++k) {
            const int32_t d = abs(F.steps[k] - was[k]);
            fastest = d > fastest ? d : fastest;
            was[k] = F.steps[k];
        }
    }
    assert_int_equal(fw_state_of(C), FW_STATE_IDLE);
    assert_int_equal(fw_fault_of(C), FW_FAULT_NONE);
    assert_true(fw_homed_of(C));
    assert_true(fastest <= 100);
}


static void stopped_trajectory_stays_stopped(void **state)
{
    (void)state;
    start();
    home();
    /* 30 points 50 ms apart, 1 mm up each, the last flagged: 30 mm in 1.5 s. */
    double p[6];
    memcpy(p, now().pose, sizeof p);
    const double z0 = p[2];
    for (int i = 1; i <= 30; ++i) {
        p[2] = z0 + 0.001 * i;
        traj_row(p, 50000, i == 1, i == 30);
    }
    run(300);
    assert_int_equal(fw_state_of(C), FW_STATE_MOVING);
    cmd(PM_STOP);
    fw_poll(C);
    assert_int_equal(fw_state_of(C), FW_STATE_STOPPING);
    const double z_stop = now().pose[2];
    int32_t at_stop[6];
    memcpy(at_stop, F.steps, sizeof at_stop);
    for (int i = 0; i < 200 && fw_state_of(C) == FW_STATE_STOPPING; ++i)
        run(10);
    assert_int_equal(fw_state_of(C), FW_STATE_IDLE);
    assert_int_equal(fw_fault_of(C), FW_FAULT_NONE);
    /* At 20 mm/s of plate a stop within the limits takes well under 2 mm; the last point was
     * 24 mm further. */
    assert_true(now().pose[2] - z_stop < 0.002);
    for (int k = 0; k < 6; ++k)
        assert_true(abs(F.steps[k] - at_stop[k]) < 2560); /* 2 mm of slide */
}

static void traj_refused_for_state_keeps_its_number(void **state)
{
    (void)state;
    start();
    home();
    double p[6];
    memcpy(p, now().pose, sizeof p);
    const double z0 = p[2];
    for (int i = 1; i <= 4; ++i) {
        p[2] = z0 + 0.0005 * i;
        traj_row(p, 50000, i == 1, i == 4);
    }
    run(50);
    assert_int_equal(fw_state_of(C), FW_STATE_MOVING);
    /* A point after the last one: refused, the trajectory takes no more. */
    p[2] = z0 + 0.001;
    const uint8_t s = seq++;
    stage(s, p);
    const int32_t v[4] = {s, 50000, PROTO_TRAJ_LAST, traj_id};
    unsigned from = F.tx_count;
    send(PM_TRAJ_COMMIT, v);
    fw_poll(C);
    uint8_t reason = 0;
    assert_int_equal(answer(from, proto_table[PM_TRAJ_COMMIT].function, &reason), 'r');
    assert_int_equal(reason, FW_REASON_STATE);
    for (int i = 0; i < 100 && fw_state_of(C) != FW_STATE_IDLE; ++i)
        run(10);
    assert_int_equal(fw_state_of(C), FW_STATE_IDLE);
    /* At rest the same commit is a row of a trajectory that has ended: it never starts another. */
    from = F.tx_count;
    send(PM_TRAJ_COMMIT, v);
    fw_poll(C);
    assert_int_equal(answer(from, proto_table[PM_TRAJ_COMMIT].function, &reason), 'r');
    assert_int_equal(reason, FW_REASON_ENDED);
    /* As the first row of a new trajectory: its staged pose and its number are still good. */
    const int32_t again[4] = {s, 50000, PROTO_TRAJ_FIRST | PROTO_TRAJ_LAST, s};
    from = F.tx_count;
    send(PM_TRAJ_COMMIT, again);
    fw_poll(C);
    assert_int_equal(answer(from, proto_table[PM_TRAJ_COMMIT].function, &reason), 'a');
    assert_int_equal(fw_state_of(C), FW_STATE_MOVING);
}

static void refused_pose_part_keeps_the_staged_pose(void **state)
{
    (void)state;
    start();
    home();
    seq = 0;
    move_to(NEAR, 500); /* the last commit: 0 */
    for (int i = 0; i < 300 && fw_state_of(C) != FW_STATE_IDLE; ++i)
        run(10);
    assert_int_equal(fw_state_of(C), FW_STATE_IDLE);
    /* Parts A and B of a pose under 100 (newer than 0), then a part C under 200: newer than 100
     * but not than 0 (200 is 56 behind it, modulo 256), so refused; then C under 100. */
    const double p[6] = {0.04, 0.0, 1.0, 0, 0, 0};
    const int32_t a[3] = {100, (int32_t)lround(p[0] * 1e6), (int32_t)lround(p[1] * 1e6)};
    const int32_t b[3] = {100, (int32_t)lround(p[2] * 1e6), (int32_t)lround(p[3] * 1e6)};
    const int32_t c200[3] = {200, 0, 0}, c100[3] = {100, 0, 0};
    send(PM_POSE_A, a);
    send(PM_POSE_B, b);
    unsigned from = F.tx_count;
    send(PM_POSE_C, c200);
    fw_poll(C);
    uint8_t reason = 0;
    assert_int_equal(answer(from, proto_table[PM_POSE_C].function, &reason), 'r');
    assert_int_equal(reason, FW_REASON_STALE);
    send(PM_POSE_C, c100);
    from = F.tx_count;
    const int32_t m[3] = {100, 0, 500};
    send(PM_MOVE_COMMIT, m);
    fw_poll(C);
    assert_int_equal(answer(from, proto_table[PM_MOVE_COMMIT].function, &reason), 'a');
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(range_reject_carries_the_seq),
        cmocka_unit_test(step_rate_leaving_no_step_is_refused),
        cmocka_unit_test(homing_speed_held_to_the_slide_limit),
        cmocka_unit_test(stopped_trajectory_stays_stopped),
        cmocka_unit_test(traj_refused_for_state_keeps_its_number),
        cmocka_unit_test(refused_pose_part_keeps_the_staged_pose),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
