/* The controller through its CAN interface, on the fake HAL: every command in every state,
 * atomic staging, malformed frames, watchdog, e-stop (command, input and interrupt), the switches'
 * meaning outside homing, bus-off, parameters and the drivers' timing. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "harness.h"

/* Every command in every state, against docs/controller.md, "Commands in each state", written
 * out here. */
static void test_state_table(void **state)
{
    (void)state;
    const fw_state states[] = {FW_STATE_DISABLED, FW_STATE_HOMING, FW_STATE_IDLE, FW_STATE_MOVING,
                               FW_STATE_STOPPING, FW_STATE_FAULT, FW_STATE_ESTOP};
    /* 'a' ack, 'r' reject (state), '-' no answer.  Order of states as above. */
    const struct {
        proto_msg cmd;
        const char *expect;
    } rows[] = {
        {PM_ESTOP, "aaaaaaa"},       {PM_STOP, "aaaaaaa"},        {PM_HOST_HEARTBEAT, "-------"},
        {PM_ENABLE, "arrrrrr"},      {PM_DISABLE, "ararraa"},     {PM_HOME, "rrarrrr"},
        {PM_CLEAR_FAULT, "rrrrraa"}, {PM_POSE_A, "-------"},      {PM_MOVE_COMMIT, "rraarrr"},
        {PM_TRAJ_COMMIT, "rrarrrr"}, {PM_PARAM_GET, "aaaaaaa"},   {PM_PARAM_SET, "arrrraa"},
        {PM_PARAM_SAVE, "arrrraa"},  {PM_INFO_GET, "aaaaaaa"},
        /* Into the bootloader only with the drives off; its own commands never (protocol.md). */
        {PM_BOOT_ENTER, "arrrraa"},  {PM_BOOT_QUERY, "rrrrrrr"},  {PM_BOOT_ERASE, "rrrrrrr"},
        {PM_BOOT_WRITE, "rrrrrrr"},  {PM_BOOT_VERIFY, "rrrrrrr"}, {PM_BOOT_START, "rrrrrrr"},
        {PM_BOOT_DATA, "rrrrrrr"},
    };
    for (size_t r = 0; r < sizeof rows / sizeof rows[0]; ++r) {
        for (size_t k = 0; k < sizeof states / sizeof states[0]; ++k) {
            const char want = rows[r].expect[k];
            reach(states[k]);
            const unsigned from = F.tx_count;
            const uint8_t s = seq++;
            switch (rows[r].cmd) {
            case PM_MOVE_COMMIT: {
                stage(s, NEAR);
                const int32_t v[3] = {s, 0, 2000};
                send(PM_MOVE_COMMIT, v);
                break;
            }
            case PM_TRAJ_COMMIT: {
                stage(s, now().pose_known ? now().pose : NEAR);
                const int32_t v[4] = {s, 50000, PROTO_TRAJ_FIRST | PROTO_TRAJ_LAST, s};
                send(PM_TRAJ_COMMIT, v);
                break;
            }
            case PM_PARAM_GET: {
                const int32_t v[1] = {FP_WATCHDOG_MS};
                send(PM_PARAM_GET, v);
                break;
            }
            case PM_PARAM_SET: {
                const int32_t v[2] = {FP_WATCHDOG_MS, 400};
                send(PM_PARAM_SET, v);
                break;
            }
            case PM_PARAM_SAVE: {
                const int32_t v[1] = {0x45564153};
                send(PM_PARAM_SAVE, v);
                break;
            }
            case PM_INFO_GET: {
                const int32_t v[1] = {0};
                send(PM_INFO_GET, v);
                break;
            }
            case PM_POSE_A: {
                const int32_t v[3] = {s, 0, 0};
                send(PM_POSE_A, v);
                break;
            }
            case PM_BOOT_ENTER: {
                const int32_t v[2] = {s, 0x544F4F42}; /* "BOOT" */
                send(PM_BOOT_ENTER, v);
                break;
            }
            case PM_BOOT_ERASE: {
                const int32_t v[2] = {s, 4096};
                send(PM_BOOT_ERASE, v);
                break;
            }
            case PM_BOOT_WRITE: {
                const int32_t v[5] = {s, 0, 128, 0, 0};
                send(PM_BOOT_WRITE, v);
                break;
            }
            case PM_BOOT_DATA: {
                const int32_t v[4] = {1, 2, 3, 4};
                send(PM_BOOT_DATA, v);
                break;
            }
            default: {
                const int32_t v[1] = {s};
                send(rows[r].cmd, v);
            }
            }
            fw_poll(C);
            uint8_t reason = 0;
            const char got = answer(from, proto_table[rows[r].cmd].function, &reason);
            if ((want == '-' ? 0 : want) != got)
                fail_msg("%s in state %d: expected %c, got %c", proto_table[rows[r].cmd].name, states[k], want,
                         got ? got : '-');
            if (got == 'r') {
                assert_int_equal(reason, FW_REASON_STATE);
                /* and says which state refused */
                assert_int_equal(reject_of(from, proto_table[rows[r].cmd].function).v[5], states[k]);
            }
            /* A BOOT_ENTER taken leaves the controller waiting for its restart, the drives off:
             * it takes nothing more, ENABLE least of all. */
            assert_int_equal(fw_boot_requested(C), rows[r].cmd == PM_BOOT_ENTER && got == 'a');
            if (fw_boot_requested(C)) {
                assert_false(fw_drives_of(C));
                const unsigned after = F.tx_count;
                const fw_state was = fw_state_of(C);
                cmd(PM_ENABLE);
                fw_poll(C);
                assert_int_equal(answer(after, proto_table[PM_ENABLE].function, NULL), 0);
                assert_int_equal(fw_state_of(C), was);
            }
        }
    }
    /* Boot accepts nothing but e-stop, parameter reads, INFO_GET and BOOT_ENTER (a controller stuck
     * in boot can still be updated). */
    for (int m = 0; m < PM_COUNT; ++m) {
        if (proto_table[m].dir != PROTO_TO_CONTROLLER)
            continue;
        const fw_reason r = fw_command_allowed((proto_msg)m, FW_STATE_BOOT);
        const int ok = m == PM_ESTOP || m == PM_HOST_HEARTBEAT || m == PM_PARAM_GET || m == PM_INFO_GET ||
                       m == PM_BOOT_ENTER;
        assert_int_equal(r == FW_REASON_NONE, ok);
    }
}

static void test_move_lands_on_target_steps(void **state)
{
    (void)state;
    reach(FW_STATE_IDLE);
    const double target[6] = {0.1, -0.05, 1.1, 0.1, -0.05, 0.2};
    const unsigned from = F.tx_count;
    move_to(target, 1000);
    run(50);
    assert_int_equal(answer(from, 0x0D, NULL), 'a');
    for (int i = 0; i < 100 && fw_state_of(C) != FW_STATE_IDLE; ++i)
        run(100);
    assert_int_equal(fw_state_of(C), FW_STATE_IDLE);
    /* The slides sit on the target's solution, to the step, in true coordinates: the fake's
     * switches are pressed at and below 256000 steps, which is where home_sw_k = 0.2 m puts them at
     * 1.28M steps/m, so the edge homing latches is the true step 256001. */
    tse_ik_result r;
    const double wire[6] = {0.1, -0.05, 1.1, 0.1, -0.05, 0.2};
    assert_int_equal(tse_ik(fw_geometry_of(C), wire, NULL, &r), TSE_OK);
    for (int k = 0; k < 6; ++k) {
        const long want = lround(r.q[k] * 1280000.0);
        assert_int_equal(F.steps[k], want);
    }
}

/* A move committed during another is blended in: the slides do not come to rest between the two,
 * and the robot ends on the second target to the step.  A third is refused while two are held. */
static void test_blended_moves(void **state)
{
    (void)state;
    reach(FW_STATE_IDLE);
    const double first[6] = {0.06, 0.0, 1.05, 0, 0, 0}, second[6] = {0.06, 0.06, 1.10, 0, 0, 0.05};
    unsigned from = F.tx_count;
    move_to(first, 1500);
    run(200);
    move_to(second, 1500);
    run(10);
    assert_int_equal(answer(from, 0x0D, NULL), 'a');
    assert_true(now().has_next);
    assert_true(now().blend_k0 < now().move.segments); /* blended, not back to back */
    from = F.tx_count;
    const double third[6] = {0, 0, 1.0, 0, 0, 0};
    move_to(third, 1500);
    fw_poll(C);
    uint8_t reason = 0;
    assert_int_equal(answer(from, 0x0D, &reason), 'r');
    assert_int_equal(reason, FW_REASON_QUEUE_FULL);
    /* Watch the steps per 10 ms until the end: once moving, never at rest until the last stretch. */
    long prev = 0;
    for (int k = 0; k < 6; ++k)
        prev += F.steps[k];
    int moving_windows = 0, rest_between = 0, started = 0, stopped = 0;
    for (int i = 0; i < 800 && fw_state_of(C) != FW_STATE_IDLE; ++i) {
        run(10);
        long now = 0, diff = 0;
        for (int k = 0; k < 6; ++k)
            now += F.steps[k];
        diff = labs(now - prev);
        int32_t steps[6];
        stepgen_positions(fw_stepgen_of(C), steps);
        (void)steps;
        if (diff > 0) {
            if (stopped)
                rest_between = 1;
            started = 1;
            ++moving_windows;
        } else if (started) {
            stopped = 1;
        }
        prev = now;
    }
    assert_int_equal(fw_state_of(C), FW_STATE_IDLE);
    assert_false(rest_between);
    assert_true(moving_windows > 100);
    tse_ik_result r;
    assert_int_equal(tse_ik(fw_geometry_of(C), second, NULL, &r), TSE_OK);
    for (int k = 0; k < 6; ++k)
        assert_int_equal(F.steps[k], lround(r.q[k] * 1280000.0));
}

static void test_staging_is_atomic(void **state)
{
    (void)state;
    reach(FW_STATE_IDLE);
    const double target[6] = {0.05, 0.02, 1.05, 0, 0, 0.1};
    uint8_t reason = 0;

    /* Two parts only. */
    uint8_t s = seq++;
    const int32_t a[3] = {s, 50000, 20000}, b[3] = {s, 1050000, 0};
    send(PM_POSE_A, a);
    send(PM_POSE_B, b);
    const int32_t m[3] = {s, 0, 1000};
    unsigned from = F.tx_count;
    send(PM_MOVE_COMMIT, m);
    fw_poll(C);
    assert_int_equal(answer(from, 0x0D, &reason), 'r');
    assert_int_equal(reason, FW_REASON_INCOMPLETE);
    assert_int_equal(fw_state_of(C), FW_STATE_IDLE);

    /* Parts of a different sequence do not complete it. */
    const int32_t c_other[3] = {(uint8_t)(s + 1), 0, 100000};
    send(PM_POSE_C, c_other);
    from = F.tx_count;
    send(PM_MOVE_COMMIT, m);
    fw_poll(C);
    assert_int_equal(answer(from, 0x0D, &reason), 'r');
    assert_int_equal(reason, FW_REASON_INCOMPLETE);

    /* Out of order is fine: C, A, B of one sequence. */
    s = (uint8_t)(s + 1);
    seq = (uint8_t)(s + 1);
    const int32_t c2[3] = {s, 0, 100000}, a2[3] = {s, 50000, 20000}, b2[3] = {s, 1050000, 0};
    send(PM_POSE_C, c2);
    send(PM_POSE_A, a2);
    send(PM_POSE_B, b2);
    /* A late part of an abandoned, older sequence (still newer than the last commit) starts the
     * staging afresh: the commit of s is then incomplete, never a mix, and a restaging works. */
    const int32_t late[3] = {(uint8_t)(s - 1), 0, 0};
    from = F.tx_count;
    send(PM_POSE_A, late);
    fw_poll(C);
    assert_int_equal(answer(from, 0x0A, &reason), 0);
    const int32_t m2[3] = {s, 0, 1000};
    from = F.tx_count;
    send(PM_MOVE_COMMIT, m2);
    fw_poll(C);
    assert_int_equal(answer(from, 0x0D, &reason), 'r');
    assert_int_equal(reason, FW_REASON_INCOMPLETE);
    assert_int_equal(fw_state_of(C), FW_STATE_IDLE);
    send(PM_POSE_C, c2);
    send(PM_POSE_A, a2);
    send(PM_POSE_B, b2);
    from = F.tx_count;
    send(PM_MOVE_COMMIT, m2);
    fw_poll(C);
    assert_int_equal(answer(from, 0x0D, NULL), 'a');
    assert_int_equal(fw_state_of(C), FW_STATE_MOVING);
    for (int k = 0; k < 6; ++k)
        assert_true(fabs(now().move.to[k] - target[k]) < 1e-12);

    /* The same sequence again is stale. */
    for (int i = 0; i < 50 && fw_state_of(C) != FW_STATE_IDLE; ++i)
        run(100);
    stage(s, target);
    from = F.tx_count;
    send(PM_MOVE_COMMIT, m2);
    fw_poll(C);
    assert_int_equal(answer(from, 0x0D, &reason), 'r');
    assert_int_equal(reason, FW_REASON_STALE);
}

/* A single stray part staged under a number ahead of the host's (a second tool, a corrupted
 * frame) must not lock the host out: the host numbers its poses one past the last accepted
 * commit, as tsectl does, and its parts and commit are accepted.  (Before, a part could not
 * displace a newer-numbered one, and every later move was refused until a restart.) */
static void test_stray_part_ahead_does_not_block_the_host(void **state)
{
    (void)state;
    reach(FW_STATE_IDLE);
    const double target[6] = {0.05, 0.02, 1.05, 0, 0, 0.1};
    for (int round = 0; round < 3; ++round) {
        const uint8_t host_seq = (uint8_t)(now().last_seq + 1u);
        const int32_t stray[3] = {(uint8_t)(host_seq + 1u + (unsigned)round * 60u), 1000, 2000};
        send(PM_POSE_B, stray);
        fw_poll(C);
        stage(host_seq, round % 2 ? NEAR : target);
        const int32_t m[3] = {host_seq, 0, 500};
        const unsigned from = F.tx_count;
        send(PM_MOVE_COMMIT, m);
        fw_poll(C);
        assert_int_equal(answer(from, 0x0D, NULL), 'a');
        for (int i = 0; i < 50 && fw_state_of(C) != FW_STATE_IDLE; ++i)
            run(100);
        assert_int_equal(fw_state_of(C), FW_STATE_IDLE);
        assert_int_equal(now().last_seq, host_seq);
    }
}

static void test_unreachable_pose_rejected_without_motion(void **state)
{
    (void)state;
    reach(FW_STATE_IDLE);
    const uint64_t pulses = F.pulses;
    const double away[6] = {0.8, 0, 1.0, 0, 0, 0};
    const unsigned from = F.tx_count;
    move_to(away, 1000);
    run(100);
    const hal_can_frame *r = fake_last(&F, 0x03, from);
    assert_non_null(r);
    assert_int_equal(r->data[0], 0x0D);
    assert_int_equal(r->data[2], FW_REASON_KINEMATICS);
    assert_true(r->data[3] >= 1 && r->data[3] <= 3);
    assert_int_not_equal(r->data[4], TSE_OK);
    assert_int_equal(fw_state_of(C), FW_STATE_IDLE);
    assert_true(F.pulses == pulses);
}

/* Malformed frames are refused with their reason and change nothing. */
static void test_malformed_frames(void **state)
{
    (void)state;
    reach(FW_STATE_IDLE);
    const fw_state st = fw_state_of(C);
    const fw_param_set params = (*fw_params_of(C));
    struct {
        uint16_t id;
        uint8_t len;
        uint8_t data[8];
        uint8_t reason;
    } cases[] = {
        {0x061, 2, {1, 2}, FW_REASON_BAD_LENGTH},                  /* ENABLE with 2 bytes */
        {0x7F1, 1, {1}, FW_REASON_UNKNOWN},                        /* no such function */
        {0x0D1, 6, {9, 7, 0xE8, 3, 0, 0}, FW_REASON_RANGE},         /* MOVE_COMMIT kind 7 */
        {0x0A1, 7, {9, 0xFF, 0xFF, 0x7F, 0, 0, 0}, FW_REASON_RANGE}, /* x = 8.4 m */
        {0x111, 4, {1, 2, 3, 4}, FW_REASON_RANGE},                 /* PARAM_SAVE without magic */
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        const unsigned from = F.tx_count;
        fake_send(&F, cases[i].id, cases[i].len, cases[i].data);
        fw_poll(C);
        uint8_t reason = 0;
        assert_int_equal(answer(from, (uint8_t)(cases[i].id >> 4), &reason), 'r');
        assert_int_equal(reason, cases[i].reason);
        assert_int_equal(fw_state_of(C), st);
        assert_memory_equal(fw_params_of(C), &params, sizeof params);
        assert_int_equal(now().stage_have, 0);
    }
    /* Other nodes' frames and the controllers' own traffic are ignored. */
    const unsigned from = F.tx_count;
    const uint8_t d[1] = {5};
    fake_send(&F, 0x072, 1, d);           /* DISABLE for node 2 */
    fake_send(&F, 0x201, 8, (uint8_t[8]){0}); /* a STATUS frame */
    fake_send(&F, 0x060, 1, d);           /* ENABLE broadcast: only stops are broadcast */
    fw_poll(C);
    assert_int_equal(F.tx_count, from + 0u);
    assert_int_equal(fw_state_of(C), FW_STATE_IDLE);
}

static void test_watchdog(void **state)
{
    (void)state;
    reach(FW_STATE_IDLE);
    fake_run(&F, C, 450);
    assert_int_equal(fw_state_of(C), FW_STATE_IDLE); /* 500 ms not yet passed */
    fake_run(&F, C, 100);
    assert_int_equal(fw_state_of(C), FW_STATE_FAULT);
    assert_int_equal(fw_fault_of(C), FW_FAULT_WATCHDOG);
    assert_false(F.enabled);
    /* Latched until cleared; clearing leaves the drives off. */
    run(200);
    assert_int_equal(fw_state_of(C), FW_STATE_FAULT);
    cmd(PM_CLEAR_FAULT);
    run(10);
    assert_int_equal(fw_state_of(C), FW_STATE_DISABLED);
    assert_int_equal(fw_fault_of(C), FW_FAULT_NONE);
}

/* Silence during a move: a controlled stop along the path, then the fault. */
static void test_watchdog_during_move_stops_smoothly(void **state)
{
    (void)state;
    reach(FW_STATE_MOVING);
    run(1000);
    fake_run(&F, C, 520);
    assert_int_equal(fw_state_of(C), FW_STATE_STOPPING);
    for (int i = 0; i < 100 && fw_state_of(C) == FW_STATE_STOPPING; ++i)
        fake_run(&F, C, 10);
    assert_int_equal(fw_state_of(C), FW_STATE_FAULT);
    assert_int_equal(fw_fault_of(C), FW_FAULT_WATCHDOG);
    assert_true(fw_homed_of(C)); /* a controlled stop keeps the zero */
}

static void test_estop_cuts_within_a_tick(void **state)
{
    (void)state;
    reach(FW_STATE_MOVING);
    run(500);
    const uint64_t before = F.pulses;
    run(10);
    assert_true(F.pulses > before); /* it was moving */
    cmd(PM_ESTOP);
    fake_run(&F, C, 1); /* the poll at the start of this tick takes the e-stop */
    const uint64_t at = F.pulses;
    fake_run(&F, C, 100);
    assert_true(F.pulses == at);
    assert_int_equal(fw_state_of(C), FW_STATE_ESTOP);
    assert_false(F.enabled);
    assert_false(fw_homed_of(C));
    /* The input too, and clearing needs it closed. */
    reach(FW_STATE_IDLE);
    F.estop_open = true;
    fake_run(&F, C, 1);
    assert_int_equal(fw_state_of(C), FW_STATE_ESTOP);
    uint8_t reason;
    const unsigned from = F.tx_count;
    cmd(PM_CLEAR_FAULT);
    fw_poll(C);
    assert_int_equal(answer(from, 0x09, &reason), 'r');
    F.estop_open = false;
    cmd(PM_CLEAR_FAULT);
    run(10);
    assert_int_equal(fw_state_of(C), FW_STATE_DISABLED);
}

/* What the switches mean outside homing.  The high-end switches are hard limits.  A low (homing)
 * switch, once homed, cross-checks the step count: pressed above home_sw_k + 0.5 mm or released
 * below home_sw_k - 0.5 mm is lost steps or a broken switch; before homing it means nothing. */
static void test_switches_outside_homing(void **state)
{
    (void)state;
    /* A high-end switch while moving: a controlled stop, then the limit fault, the zero dropped. */
    reach(FW_STATE_MOVING);
    F.forced_limits = 1u << (8 + 3);
    run(10);
    assert_int_equal(fw_state_of(C), FW_STATE_STOPPING);
    run(500);
    assert_int_equal(fw_state_of(C), FW_STATE_FAULT);
    assert_int_equal(fw_fault_of(C), FW_FAULT_LIMIT);
    assert_false(fw_homed_of(C));
    /* Slide 4's homing switch pressed while its count says about 0.4 m, far above its 0.2 m. */
    reach(FW_STATE_MOVING);
    assert_true(F.steps[3] > FAKE_SWITCH_AT + 640);
    F.forced_limits = 1u << 3;
    run(10);
    assert_int_equal(fw_state_of(C), FW_STATE_STOPPING);
    run(500);
    assert_int_equal(fw_state_of(C), FW_STATE_FAULT);
    assert_int_equal(fw_fault_of(C), FW_FAULT_LIMIT);
    assert_false(fw_homed_of(C));
    /* Before homing a pressed homing switch is only where the slide is: no fault, no flag. */
    start();
    cmd(PM_ENABLE);
    run(20);
    F.forced_limits = 0x3F;
    unsigned from = F.tx_count;
    run(300);
    assert_int_equal(fw_state_of(C), FW_STATE_IDLE);
    assert_int_equal(fw_fault_of(C), FW_FAULT_NONE);
    const hal_can_frame *st = fake_last(&F, 0x20, from);
    assert_non_null(st);
    assert_int_equal(st->data[2] & 8u, 0);
    /* The STATUS flag is set by a high-end switch (which also faults, as the controller is active). */
    F.forced_limits = 1u << 8;
    from = F.tx_count;
    run(300);
    st = fake_last(&F, 0x20, from);
    assert_non_null(st);
    assert_int_equal(st->data[2] & 8u, 8u);
    assert_int_equal(fw_fault_of(C), FW_FAULT_LIMIT);
}

/* The cross-check's tolerance is 0.5 mm, 640 steps at 1.28M steps/m.  Switches placed 0.3 mm
 * above, 0.7 mm above, 0.3 mm below and 0.7 mm below where homing leaves slides 1 to 4 (home_s),
 * 5 and 6 at it;
 * then each switch is moved by 1 mm across its slide, as lost steps would move the slide: within
 * the tolerance the disagreement is let pass, beyond it it is a limit fault. */
static void test_switch_tolerance(void **state)
{
    (void)state;
    start();
    const long at_home = lround(fw_geometry_of(C)->home_s * 1280000.0); /* steps at home */
    const int32_t home_um = (int32_t)lround(fw_geometry_of(C)->home_s * 1e6);
    const int32_t sw_um[6] = {home_um - 300, home_um - 700, home_um + 300, home_um + 700, home_um, home_um};
    /* The switches written whole, past the wire's one-at-a-time PARAM_SET: the check refuses a
     * set with some switches near home and the others at 0.2 m (homing's final move from there
     * leaves the workspace), and every set on the way to this one is such a set.  So the set is
     * stored, and the controller started again finds it (as after a PARAM_SAVE). */
    fw_param_set ps = *fw_params_of(C);
    for (int k = 0; k < 6; ++k)
        ps.v[FP_HOME_SW_1 + k] = sw_um[k];
    assert_int_equal(fw_params_judge(&ps).rule, FW_RULE_NONE);
    fw_hal hal;
    fake_hal_init(&F, &hal);
    F.storage_len = (int)fw_params_serialize(&ps, F.storage, sizeof F.storage);
    assert_true(F.storage_len > 0);
    for (int k = 0; k < 6; ++k) {
        F.switch_at[k] = (int32_t)((int64_t)sw_um[k] * 128 / 100); /* pressed at and below */
        F.steps[k] = F.switch_at[k] + 3000;
    }
    restart(&hal);
    for (int k = 0; k < 6; ++k)
        assert_int_equal(fw_params_of(C)->v[FP_HOME_SW_1 + k], sw_um[k]);
    for (int round = 0; round < 2; ++round) {
        if (round == 1) {
            /* Again from a fresh homing, for slide 4 (the fault of slide 2 ended the first). */
            for (int k = 0; k < 6; ++k)
                F.switch_at[k] = (int32_t)((int64_t)sw_um[k] * 128 / 100);
            cmd(PM_CLEAR_FAULT);
            run(10);
        }
        home();
        for (int k = 0; k < 6; ++k)
            assert_int_equal(F.steps[k], at_home);
        run(100);
        assert_int_equal(fw_state_of(C), FW_STATE_IDLE);
        if (round == 0) {
            /* Slide 1 (0.3 mm above its switch) now reads pressed: within the tolerance. */
            F.switch_at[0] += 1280;
            assert_true(F.steps[0] <= F.switch_at[0]);
            /* Slide 3 (0.3 mm below) now reads released: within the tolerance. */
            F.switch_at[2] -= 1280;
            assert_true(F.steps[2] > F.switch_at[2]);
            run(100);
            assert_int_equal(fw_state_of(C), FW_STATE_IDLE);
            assert_true(fw_homed_of(C));
            /* Slide 2 (0.7 mm above) reads pressed: beyond it. */
            F.switch_at[1] += 1280;
        } else {
            /* Slide 4 (0.7 mm below) reads released: beyond it. */
            F.switch_at[3] -= 1280;
        }
        run(10);
        assert_int_equal(fw_state_of(C), FW_STATE_FAULT);
        assert_int_equal(fw_fault_of(C), FW_FAULT_LIMIT);
        assert_false(fw_homed_of(C));
    }
}

/* Homing from below the switches: every slide starts pressed, leaves its switch at the homing
 * speed, comes back, and its coordinate is set at the edge, so the slides end at home_s to the
 * step in true coordinates. */
static void test_homing_from_below(void **state)
{
    (void)state;
    start();
    for (int k = 0; k < 6; ++k)
        F.steps[k] = FAKE_SWITCH_AT - 20000 - 1000 * k; /* 16 to 20 mm below */
    home();
    for (int k = 0; k < 6; ++k)
        assert_int_equal(F.steps[k], lround(fw_geometry_of(C)->home_s * 1280000.0));
}

/* Each slide's own switch position: slide 6's switch 5 cm higher than the others. */
static void test_homing_per_slide_switch(void **state)
{
    (void)state;
    start();
    assert_int_equal(set_param(FP_HOME_SW_6, 250000, NULL, NULL), 'a');
    F.switch_at[5] = 320000; /* 0.25 m */
    F.steps[5] = 330000;
    home();
    for (int k = 0; k < 6; ++k)
        assert_int_equal(F.steps[k], lround(fw_geometry_of(C)->home_s * 1280000.0));
}

static void test_bus_off(void **state)
{
    (void)state;
    reach(FW_STATE_IDLE);
    F.can_state.bus_off = true;
    run(10);
    assert_int_equal(fw_fault_of(C), FW_FAULT_BUS_OFF);
}

/* A bus-off that automatic recovery ended before the controller looked: only its count moved,
 * and a status frame read the CAN state in between.  It is a fault all the same. */
static void test_bus_off_recovered_between_looks(void **state)
{
    (void)state;
    reach(FW_STATE_IDLE);
    run(10);
    assert_int_equal(fw_state_of(C), FW_STATE_IDLE);
    F.can_state.bus_off = false;
    F.can_state.bus_off_events = 1;
    run(10);
    assert_int_equal(fw_state_of(C), FW_STATE_FAULT);
    assert_int_equal(fw_fault_of(C), FW_FAULT_BUS_OFF);
}

/* The drivers' timing: programmed through hal_stepper.timing at start-up and on every accepted
 * set; DIR set-up turned into whole step interrupts (here 100 kHz, 10 us each), rounded up; a STEP
 * pulse refused unless it ends within its 10 us tick and leaves a low time as long as the high
 * time before the same slide's next step. */
static void test_driver_timing(void **state)
{
    (void)state;
    start();
    assert_int_equal(F.timing_calls, 1);
    assert_int_equal(F.pulse_ns, (uint32_t)fw_param_table[FP_STEP_PULSE_NS].def);
    assert_int_equal(F.dir_setup_ns, (uint32_t)fw_param_table[FP_DIR_SETUP_NS].def);
    assert_int_equal(fw_stepgen_of(C)->cfg.dir_setup_ticks, 2); /* 5 us is half a tick: one, plus one of margin */
    const struct {
        int32_t ns;
        uint32_t ticks;
    } setups[] = {{25000, 4}, {20000, 3}, {20001, 4}, {1, 2}, {0, 1}};
    for (size_t i = 0; i < sizeof setups / sizeof setups[0]; ++i) {
        assert_int_equal(set_param(FP_DIR_SETUP_NS, setups[i].ns, NULL, NULL), 'a');
        assert_int_equal(fw_stepgen_of(C)->cfg.dir_setup_ticks, setups[i].ticks);
        assert_int_equal(F.dir_setup_ns, (uint32_t)setups[i].ns);
    }
    assert_int_equal(F.timing_calls, 6);
    /* 1 ms is the whole 100-tick segment: no room for a step after a direction change. */
    uint8_t reason = 0, field = 0;
    assert_int_equal(set_param(FP_DIR_SETUP_NS, 1000000, &reason, &field), 'r');
    assert_int_equal(reason, FW_REASON_PARAM_SET);
    assert_int_equal(field, FP_DIR_SETUP_NS);
    assert_int_equal(fw_params_of(C)->v[FP_DIR_SETUP_NS], 0);
    assert_int_equal(F.timing_calls, 6);
    /* step_rate_max 200k at 100 kHz: steps may come on consecutive 10 us ticks, so 5 us high and
     * 5 us low is the longest pulse. */
    assert_int_equal(set_param(FP_STEP_PULSE_NS, 5000, NULL, NULL), 'a');
    assert_int_equal(F.pulse_ns, 5000);
    assert_int_equal(set_param(FP_STEP_PULSE_NS, 5001, &reason, &field), 'r');
    assert_int_equal(reason, FW_REASON_PARAM_SET);
    assert_int_equal(field, FP_STEP_PULSE_NS);
    assert_int_equal(fw_params_of(C)->v[FP_STEP_PULSE_NS], 5000);
    assert_int_equal(F.pulse_ns, 5000);
    /* step_rate_max 50k: two ticks between steps, 20 us; the pulse must still end within its
     * own 10 us tick, so 9999 ns fits and 10000 does not. */
    assert_int_equal(set_param(FP_STEP_RATE_MAX, 50000, NULL, NULL), 'a');
    assert_int_equal(fw_stepgen_of(C)->cfg.min_step_interval, 2);
    assert_int_equal(set_param(FP_STEP_PULSE_NS, 9999, NULL, NULL), 'a');
    assert_int_equal(set_param(FP_STEP_PULSE_NS, 10000, &reason, &field), 'r');
    assert_int_equal(reason, FW_REASON_PARAM_SET);
    /* Nor may the step rate come back up under the long pulse. */
    assert_int_equal(set_param(FP_STEP_RATE_MAX, 200000, &reason, &field), 'r');
    assert_int_equal(field, FP_STEP_RATE_MAX);
    assert_int_equal(fw_stepgen_of(C)->cfg.min_step_interval, 2);
    /* The CAN rate: one of four, stored only. */
    assert_int_equal(set_param(FP_CAN_KBPS, 300, &reason, &field), 'r');
    assert_int_equal(reason, FW_REASON_PARAM_RANGE);
    assert_int_equal(field, FP_CAN_KBPS);
    assert_int_equal(set_param(FP_CAN_KBPS, 250, NULL, NULL), 'a');
    assert_int_equal(fw_params_of(C)->v[FP_CAN_KBPS], 250);
}

/* A change of a switch position or of the step size drops the zero: it was set against the old
 * ones.  Other parameters keep it. */
static void test_switch_change_needs_homing(void **state)
{
    (void)state;
    const uint16_t ids[2] = {FP_HOME_SW_2, FP_STEPS_PER_M};
    const int32_t values[2] = {210000, 1280001};
    for (int i = 0; i < 2; ++i) {
        reach(FW_STATE_IDLE);
        cmd(PM_DISABLE);
        run(10);
        assert_int_equal(fw_state_of(C), FW_STATE_DISABLED);
        assert_true(fw_homed_of(C));
        assert_int_equal(set_param(FP_WATCHDOG_MS, 400, NULL, NULL), 'a');
        assert_true(fw_homed_of(C));
        assert_int_equal(set_param(ids[i], values[i], NULL, NULL), 'a');
        assert_false(fw_homed_of(C));
    }
}

/* The e-stop interrupt (fw_estop_isr) from the fake HAL, once, at a chosen point. */
static bool isr_armed;
static fake_hook_point isr_at;
static unsigned isr_head; /* setpoints pushed when it came */

static void estop_interrupt(void *arg, fake_hook_point at)
{
    if (!isr_armed || at != isr_at)
        return;
    isr_armed = false;
    fw_estop_isr(arg);
    isr_head = atomic_load(&fw_stepgen_of(C)->head);
}

static void arm_interrupt(fake_hook_point at)
{
    F.hook = estop_interrupt;
    F.hook_arg = C;
    isr_at = at;
    isr_armed = true;
}

/* The interrupt inside a control tick, after it began and before it queues its setpoint (while
 * it reads the bus state; the tick reads no clock since the watchdog judges by the thread's reads
 * of the bus), three times over: the setpoint the tick still pushes is never stepped, the drives
 * are off at once, and the next control tick (never the thread) completes the e-stop. */
static void test_estop_interrupt_mid_tick(void **state)
{
    (void)state;
    const fake_hook_point points[] = {FAKE_AT_CAN_STATE, FAKE_AT_CAN_STATE, FAKE_AT_CAN_STATE};
    for (int i = 0; i < 3; ++i) {
        reach(FW_STATE_MOVING);
        run(500);
        heartbeat();
        fw_poll(C); /* the poll before the tick, as fake_run does it */
        const uint64_t pulses = F.pulses;
        assert_true(F.enabled);
        arm_interrupt(points[i]);
        fw_control_tick(C);
        assert_false(isr_armed);                          /* it came */
        assert_false(F.enabled);                          /* drives off in the interrupt */
        assert_true(atomic_load(&fw_stepgen_of(C)->head) > isr_head); /* and the tick pushed after it */
        assert_int_equal(fw_state_of(C), FW_STATE_MOVING);       /* not completed yet */
        for (int t = 0; t < 300; ++t)
            fw_step_tick(C);
        assert_true(F.pulses == pulses);
        fw_poll(C); /* the thread leaves the tick's state alone */
        assert_int_equal(fw_state_of(C), FW_STATE_MOVING);
        fw_control_tick(C); /* the next tick completes it */
        assert_int_equal(fw_state_of(C), FW_STATE_ESTOP);
        assert_int_equal(fw_fault_of(C), FW_FAULT_ESTOP);
        assert_true(stepgen_idle(fw_stepgen_of(C)));
        assert_false(fw_homed_of(C));
        assert_false(F.enabled);
        fake_run(&F, C, 100);
        assert_true(F.pulses == pulses);
        F.hook = NULL;
    }
}

/* The interrupt in the middle of a segment: the steps left of it never come. */
static void test_estop_interrupt_mid_segment(void **state)
{
    (void)state;
    reach(FW_STATE_MOVING);
    run(500);
    heartbeat();
    fw_poll(C);
    fw_control_tick(C);
    uint64_t pulses = F.pulses;
    for (int t = 0; t < 50; ++t)
        fw_step_tick(C);
    assert_true(fw_stepgen_of(C)->running);
    assert_true(F.pulses > pulses); /* it was stepping */
    pulses = F.pulses;
    fw_estop_isr(C);
    for (int t = 0; t < 500; ++t)
        fw_step_tick(C);
    assert_true(F.pulses == pulses);
    fw_control_tick(C);
    assert_int_equal(fw_state_of(C), FW_STATE_ESTOP);
    assert_false(F.enabled);
}

/* The interrupt while a poll reads a frame: the frame after it meets the e-stop state, so an
 * ENABLE is refused and the drives stay off. */
static void test_estop_interrupt_mid_poll(void **state)
{
    (void)state;
    reach(FW_STATE_DISABLED);
    const unsigned from = F.tx_count;
    cmd(PM_ENABLE);
    arm_interrupt(FAKE_AT_RECEIVE);
    fw_poll(C);
    F.hook = NULL;
    assert_false(isr_armed);
    uint8_t reason = 0;
    assert_int_equal(answer(from, 0x06, &reason), 'r');
    assert_int_equal(reason, FW_REASON_STATE);
    assert_int_equal(fw_state_of(C), FW_STATE_ESTOP);
    assert_false(F.enabled);
}

/* The interrupt just as an ENABLE switches the drives on (after the command was taken, before the
 * output changes): the drives end up off all the same, and the next tick completes the e-stop. */
static void test_estop_interrupt_during_enable(void **state)
{
    (void)state;
    reach(FW_STATE_DISABLED);
    cmd(PM_ENABLE);
    arm_interrupt(FAKE_AT_ENABLE);
    fw_poll(C);
    F.hook = NULL;
    assert_false(isr_armed);
    assert_false(F.enabled);
    fw_control_tick(C);
    assert_int_equal(fw_state_of(C), FW_STATE_ESTOP);
    assert_false(F.enabled);
}

/* The interrupt in a control tick after it looked for one (while it reads the bus state), in
 * fault, the input closed again before a CLEAR_FAULT sent for the fault: that CLEAR_FAULT was
 * judged before the e-stop latched, so it is refused `state` and the e-stop shows; one sent after
 * it clears it.  (The controller fuzzer found the e-stop cleared unseen.) */
static void test_estop_interrupt_before_clear_fault(void **state)
{
    (void)state;
    reach(FW_STATE_FAULT);
    const uint8_t fault = (uint8_t)fw_fault_of(C);
    arm_interrupt(FAKE_AT_CAN_STATE);
    fw_control_tick(C);
    F.hook = NULL;
    assert_false(isr_armed);
    assert_int_equal(fw_state_of(C), FW_STATE_FAULT); /* not completed yet */
    assert_int_equal(fw_fault_of(C), fault);
    unsigned from = F.tx_count;
    cmd(PM_CLEAR_FAULT);
    fw_poll(C);
    uint8_t reason = 0;
    assert_int_equal(answer(from, 0x09, &reason), 'r');
    assert_int_equal(reason, FW_REASON_STATE);
    assert_int_equal(fw_state_of(C), FW_STATE_ESTOP);
    assert_int_equal(fw_fault_of(C), FW_FAULT_ESTOP);
    assert_false(F.enabled);
    from = F.tx_count;
    cmd(PM_CLEAR_FAULT);
    fw_poll(C);
    assert_int_equal(answer(from, 0x09, NULL), 'a');
    assert_int_equal(fw_state_of(C), FW_STATE_DISABLED);
}

static void test_params_over_can(void **state)
{
    (void)state;
    start();
    unsigned from = F.tx_count;
    const int32_t set[2] = {FP_SLIDE_VMAX, 150000};
    send(PM_PARAM_SET, set);
    fw_poll(C);
    assert_int_equal(answer(from, 0x10, NULL), 'a');
    const hal_can_frame *v = fake_last(&F, 0x27, from);
    assert_non_null(v);
    assert_int_equal(v->data[2] | v->data[3] << 8 | v->data[4] << 16, 150000);
    /* A value that breaks the set changes nothing. */
    from = F.tx_count;
    const int32_t bad[2] = {FP_ALPHA_MIN, 1400000};
    send(PM_PARAM_SET, bad);
    fw_poll(C);
    uint8_t reason;
    assert_int_equal(answer(from, 0x10, &reason), 'r');
    assert_int_equal(reason, FW_REASON_PARAM_SET);
    assert_int_equal(fw_params_of(C)->v[FP_ALPHA_MIN], fw_param_table[FP_ALPHA_MIN].def);
    /* Saved, and found again at the next start. */
    const int32_t magic[1] = {0x45564153};
    send(PM_PARAM_SAVE, magic);
    fw_poll(C);
    const uint8_t saved[256];
    memcpy((void *)saved, F.storage, sizeof saved);
    const int len = F.storage_len;
    fw_hal hal;
    fake_hal_init(&F, &hal);
    memcpy(F.storage, saved, sizeof saved);
    F.storage_len = len;
    restart(&hal);
    assert_int_equal(fw_params_of(C)->v[FP_SLIDE_VMAX], 150000);
    /* A failing store is reported. */
    F.storage_fails = true;
    from = F.tx_count;
    send(PM_PARAM_SAVE, magic);
    fw_poll(C);
    assert_int_equal(answer(from, 0x11, &reason), 'r');
    assert_int_equal(reason, FW_REASON_STORAGE);
}

static void test_status_period(void **state)
{
    (void)state;
    start();
    const unsigned from = F.tx_count;
    run(1000);
    unsigned n = 0;
    for (unsigned i = from; i < F.tx_count; ++i)
        if ((F.tx[i].id >> 4) == 0x20)
            ++n;
    assert_true(n >= 9 && n <= 11); /* every 100 ms */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_state_table),
        cmocka_unit_test(test_move_lands_on_target_steps),
        cmocka_unit_test(test_blended_moves),
        cmocka_unit_test(test_staging_is_atomic),
        cmocka_unit_test(test_stray_part_ahead_does_not_block_the_host),
        cmocka_unit_test(test_unreachable_pose_rejected_without_motion),
        cmocka_unit_test(test_malformed_frames),
        cmocka_unit_test(test_watchdog),
        cmocka_unit_test(test_watchdog_during_move_stops_smoothly),
        cmocka_unit_test(test_estop_cuts_within_a_tick),
        cmocka_unit_test(test_switches_outside_homing),
        cmocka_unit_test(test_switch_tolerance),
        cmocka_unit_test(test_homing_from_below),
        cmocka_unit_test(test_homing_per_slide_switch),
        cmocka_unit_test(test_bus_off),
        cmocka_unit_test(test_bus_off_recovered_between_looks),
        cmocka_unit_test(test_driver_timing),
        cmocka_unit_test(test_switch_change_needs_homing),
        cmocka_unit_test(test_estop_interrupt_mid_tick),
        cmocka_unit_test(test_estop_interrupt_mid_segment),
        cmocka_unit_test(test_estop_interrupt_mid_poll),
        cmocka_unit_test(test_estop_interrupt_during_enable),
        cmocka_unit_test(test_estop_interrupt_before_clear_fault),
        cmocka_unit_test(test_params_over_can),
        cmocka_unit_test(test_status_period),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
