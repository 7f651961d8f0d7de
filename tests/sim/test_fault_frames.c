/* Frames to the controller lost, duplicated, reordered, delayed and corrupted by the fault layer,
 * with the controller, the real plant and the rig's checks after every period (sim_rig.h).  What
 * docs/protocol.md promises: every command that reaches the controller gets one ACK or REJECT
 * (pose parts and heartbeats only a REJECT), nothing of a refused command is applied, a partial
 * or stale pose is never applied.  And what it cannot promise: a frame that never arrives gets no
 * answer, and a corruption that leaves a valid command is that command. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "sim_rig.h"

#define FN(m) (proto_table[m].function)

static sim_rig R;

/* Two poses inside the workspace (tse-kin ik: every slide between 0.37 and 0.48 m). */
static const double TARGET[6] = {0.05, 0.0, 1.0, 0.0, 0.0, 0.0};
static const double OTHER[6] = {-0.05, 0.03, 1.1, 0.0, 0.0, 0.1};

static void ready(void)
{
    rig_boot(&R, 0.205); /* just above the homing switches: homing is short */
    rig_home(&R);
}

/* One control period in which every frame the controller takes off the bus suffers fault k. */
static void tick_with(fault_can_kind k)
{
    R.can.cfg.p[k] = 1.0;
    rig_tick(&R);
    R.can.cfg.p[k] = 0.0;
}

static void part(proto_msg m, uint8_t s, const double p[6])
{
    const int i = 2 * (m - PM_POSE_A);
    const int32_t v[3] = {s, (int32_t)lround(p[i] * 1e6), (int32_t)lround(p[i + 1] * 1e6)};
    rig_send(&R, m, v);
}

static void commit(uint8_t s, int32_t ms)
{
    const int32_t v[3] = {s, 0, ms};
    rig_send(&R, PM_MOVE_COMMIT, v);
}

/* The n-th (from 0) ACK or REJECT for `function` since log index `from`: 'a', 'r' (reason and
 * sequence number in *reason, *seq) or 0. */
static char nth(unsigned from, uint8_t function, unsigned n, uint8_t *reason, uint8_t *seq)
{
    for (unsigned i = from; i < R.nlog; ++i) {
        const hal_can_frame *f = &R.log[i % RIG_LOG].f;
        const uint8_t fn = (uint8_t)(f->id >> PROTO_NODE_BITS);
        if ((fn != FN(PM_ACK) && fn != FN(PM_REJECT)) || f->data[0] != function || n--)
            continue;
        if (reason)
            *reason = f->data[2];
        if (seq)
            *seq = f->data[1];
        return fn == FN(PM_ACK) ? 'a' : 'r';
    }
    return 0;
}

static void lands_on(const double p[6])
{
    rig_run(&R, 10);
    assert_true(rig_until(&R, FW_STATE_IDLE, 30000));
    assert_true(rig_plate_at(&R, p));
}

static void test_dropped(void **state)
{
    (void)state;
    ready();
    const unsigned from = R.nlog;
    /* A command lost on the way gets no answer, and nothing happens: the host must notice the
     * silence (tsectl waits for the ACK). */
    rig_cmd(&R, PM_HOME);
    tick_with(FAULT_DROP);
    rig_run(&R, 200);
    assert_int_equal(rig_answers(&R, from, FN(PM_HOME)), 0);
    assert_int_equal(fw_state_of(R.fw), FW_STATE_IDLE);
    /* A lost pose part: its commit finds the pose incomplete, and nothing moves. */
    const uint64_t pulses = R.plant.pulses;
    const uint8_t s = R.seq++;
    part(PM_POSE_A, s, OTHER);
    rig_tick(&R);
    part(PM_POSE_B, s, OTHER);
    tick_with(FAULT_DROP);
    part(PM_POSE_C, s, OTHER);
    commit(s, 1500);
    rig_run(&R, 100);
    uint8_t reason = 0;
    assert_int_equal(rig_answer(&R, from, FN(PM_MOVE_COMMIT), s, &reason), 'r');
    assert_int_equal(reason, FW_REASON_INCOMPLETE);
    assert_int_equal(fw_state_of(R.fw), FW_STATE_IDLE);
    assert_true(R.plant.pulses == pulses);
    assert_int_equal(R.can.stats.faults[FAULT_DROP], 2);
    /* The pose whole under a new number is taken, and the plate lands on it. */
    const uint8_t s2 = rig_move(&R, OTHER, 1500);
    lands_on(OTHER);
    assert_int_equal(rig_answer(&R, from, FN(PM_MOVE_COMMIT), s2, NULL), 'a');
}

static void test_duplicated(void **state)
{
    (void)state;
    ready();
    unsigned from = R.nlog;
    /* A duplicated commit is a second command: the first is taken, the second refused as stale,
     * and the robot makes one move. */
    const uint8_t s = R.seq++;
    rig_stage(&R, s, TARGET);
    rig_tick(&R);
    commit(s, 1500);
    tick_with(FAULT_DUP);
    lands_on(TARGET);
    uint8_t reason = 0, sq = 0;
    assert_int_equal(rig_answers(&R, from, FN(PM_MOVE_COMMIT)), 2);
    assert_int_equal(nth(from, FN(PM_MOVE_COMMIT), 0, NULL, &sq), 'a');
    assert_int_equal(sq, s);
    assert_int_equal(nth(from, FN(PM_MOVE_COMMIT), 1, &reason, &sq), 'r');
    assert_int_equal(reason, FW_REASON_STALE);
    assert_int_equal(sq, s);
    /* A duplicated STOP during a move: both acknowledged, one controlled stop within the limits
     * (the rig's plant checks). */
    rig_move(&R, OTHER, 2000);
    rig_run(&R, 500);
    assert_int_equal(fw_state_of(R.fw), FW_STATE_MOVING);
    from = R.nlog;
    rig_cmd(&R, PM_STOP);
    tick_with(FAULT_DUP);
    assert_int_equal(fw_state_of(R.fw), FW_STATE_STOPPING);
    assert_int_equal(nth(from, FN(PM_STOP), 0, NULL, NULL), 'a');
    assert_int_equal(nth(from, FN(PM_STOP), 1, NULL, NULL), 'a');
    assert_true(rig_until(&R, FW_STATE_IDLE, 5000));
    /* A duplicated ENABLE: the copy finds the robot enabled already. */
    rig_cmd(&R, PM_DISABLE);
    rig_run(&R, 10);
    assert_int_equal(fw_state_of(R.fw), FW_STATE_DISABLED);
    from = R.nlog;
    rig_cmd(&R, PM_ENABLE);
    tick_with(FAULT_DUP);
    assert_int_equal(nth(from, FN(PM_ENABLE), 0, NULL, NULL), 'a');
    assert_int_equal(nth(from, FN(PM_ENABLE), 1, &reason, NULL), 'r');
    assert_int_equal(reason, FW_REASON_STATE);
    assert_int_equal(fw_state_of(R.fw), FW_STATE_IDLE);
    assert_int_equal(R.can.stats.faults[FAULT_DUP], 3);
}

static void test_reordered(void **state)
{
    (void)state;
    ready();
    const unsigned from = R.nlog;
    /* The last pose part overtaken by its commit: the commit is refused as incomplete and the
     * number is not spent, so the host may commit it again once the part is in. */
    const uint64_t pulses = R.plant.pulses;
    const uint8_t s = R.seq++;
    part(PM_POSE_A, s, OTHER);
    part(PM_POSE_B, s, OTHER);
    rig_tick(&R);
    part(PM_POSE_C, s, OTHER);
    tick_with(FAULT_REORDER);
    commit(s, 1500);
    rig_tick(&R);
    uint8_t reason = 0;
    assert_int_equal(rig_answer(&R, from, FN(PM_MOVE_COMMIT), s, &reason), 'r');
    assert_int_equal(reason, FW_REASON_INCOMPLETE);
    assert_int_equal(fw_state_of(R.fw), FW_STATE_IDLE);
    assert_true(R.plant.pulses == pulses);
    assert_int_equal(R.can.stats.faults[FAULT_REORDER], 1);
    assert_int_equal(R.can.nheld, 0); /* the part came in right after the commit */
    commit(s, 1500);
    lands_on(OTHER);
    assert_int_equal(rig_answers(&R, from, FN(PM_MOVE_COMMIT)), 2);
    assert_int_equal(nth(from, FN(PM_MOVE_COMMIT), 1, NULL, NULL), 'a');
}

static void test_delayed(void **state)
{
    (void)state;
    ready();
    const unsigned from = R.nlog;
    /* The parts of one pose held 50 ms; meanwhile a newer pose is staged and committed.  The late
     * parts arrive stale: each refused, none applied: the plate lands on the newer pose. */
    R.can.cfg.delay_us = 50000;
    const uint8_t old = R.seq++;
    rig_stage(&R, old, OTHER);
    tick_with(FAULT_DELAY);
    assert_int_equal(R.can.nheld, 3);
    const uint8_t s = rig_move(&R, TARGET, 1500);
    rig_tick(&R);
    assert_int_equal(rig_answer(&R, from, FN(PM_MOVE_COMMIT), s, NULL), 'a');
    rig_run(&R, 60);
    assert_int_equal(R.can.nheld, 0);
    for (proto_msg m = PM_POSE_A; m <= PM_POSE_C; ++m) {
        uint8_t reason = 0;
        assert_int_equal(rig_answer(&R, from, FN(m), old, &reason), 'r');
        assert_int_equal(reason, FW_REASON_STALE);
    }
    lands_on(TARGET);
}

static hal_can_frame delivered; /* the latest frame the controller took */

static void remember(void *arg, fault_can_tap what, const hal_can_frame *f)
{
    (void)arg;
    if (what == FAULT_TAP_DELIVERED)
        delivered = *f;
}

/* A frame whose length changed is refused for it, naming its function, and nothing happens. */
static void test_corrupted_length(void **state)
{
    (void)state;
    ready();
    R.can.cfg.corrupt_how = FAULT_CORRUPT_LENGTH;
    const uint64_t pulses = R.plant.pulses;
    const proto_msg cmds[] = {PM_STOP, PM_HOME, PM_DISABLE, PM_ESTOP, PM_PARAM_GET, PM_MOVE_COMMIT};
    const uint8_t s = R.seq++;
    rig_stage(&R, s, OTHER);
    rig_tick(&R);
    for (size_t i = 0; i < sizeof cmds / sizeof cmds[0]; ++i) {
        const unsigned from = R.nlog;
        const int32_t v[3] = {s, 0, 1500}; /* seq (or parameter 0), then the commit's kind and time */
        rig_send(&R, cmds[i], v);
        tick_with(FAULT_CORRUPT);
        uint8_t reason = 0, sq = 0xFF;
        assert_int_equal(nth(from, FN(cmds[i]), 0, &reason, &sq), 'r');
        assert_int_equal(reason, FW_REASON_BAD_LENGTH);
        assert_int_equal(sq, 0); /* an undecodable frame has no sequence number */
        assert_int_equal(rig_answers(&R, from, FN(cmds[i])), 1);
        assert_int_equal(fw_state_of(R.fw), FW_STATE_IDLE);
        assert_true(fw_homed_of(R.fw));
    }
    assert_int_equal(R.can.stats.corrupt_length, 6);
    rig_run(&R, 100);
    assert_true(R.plant.pulses == pulses);
}

/* A frame whose identifier changed to another node's is not for this controller: no answer and
 * nothing done.  (Changed to another function, it is that function's frame.) */
static void test_corrupted_identifier(void **state)
{
    (void)state;
    ready();
    R.can.cfg.corrupt_how = FAULT_CORRUPT_ID;
    R.can.cfg.tap = remember;
    unsigned other_node = 0;
    for (int i = 0; i < 24; ++i) {
        const unsigned from = R.nlog;
        const fw_state s0 = fw_state_of(R.fw);
        rig_cmd(&R, PM_HOME);
        tick_with(FAULT_CORRUPT);
        assert_int_not_equal(delivered.id, proto_id(PM_HOME, 1));
        if ((delivered.id & PROTO_NODE_MASK) != 1) {
            ++other_node;
            for (unsigned j = from; j < R.nlog; ++j) {
                const uint8_t fn = (uint8_t)(R.log[j % RIG_LOG].f.id >> PROTO_NODE_BITS);
                assert_true(fn != FN(PM_ACK) && fn != FN(PM_REJECT));
            }
            assert_int_equal(fw_state_of(R.fw), s0);
        }
    }
    /* No HOME reached it whole: still idle, homed, at rest. */
    assert_int_equal(fw_state_of(R.fw), FW_STATE_IDLE);
    assert_true(fw_homed_of(R.fw));
    print_message("identifier corrupted 24 times, %u of them to another node\n", other_node);
    assert_true(other_node > 0);
}

/* A flipped payload bit that leaves a valid pose cannot be told from that pose: the controller
 * moves there.  Classic CAN's CRC is what keeps such frames off a real bus; the controller checks
 * only lengths, ranges, sequence numbers and the workspace. */
static void test_corrupted_payload(void **state)
{
    (void)state;
    ready();
    R.can.cfg.corrupt_how = FAULT_CORRUPT_PAYLOAD;
    R.can.cfg.tap = remember;
    unsigned elsewhere = 0, refused = 0;
    for (uint64_t trial = 1; trial <= 8; ++trial) {
        fault_rng_seed(&R.can.rng, trial);
        const unsigned from = R.nlog;
        const uint64_t pulses = R.plant.pulses;
        double want[6];
        memcpy(want, trial % 2 ? TARGET : OTHER, sizeof want);
        const uint8_t s = R.seq++;
        part(PM_POSE_A, s, want);
        tick_with(FAULT_CORRUPT);
        const hal_can_frame got = delivered;
        part(PM_POSE_B, s, want);
        part(PM_POSE_C, s, want);
        commit(s, 1500);
        rig_run(&R, 10);
        proto_message m;
        const proto_error e = proto_decode(&got, PROTO_TO_CONTROLLER, &m);
        uint8_t reason = 0;
        const char a = rig_answer(&R, from, FN(PM_MOVE_COMMIT), s, &reason);
        if (e.reason != FW_REASON_NONE || m.v[0] != s) {
            /* Out of range, or staged under another number: this pose is incomplete. */
            assert_int_equal(a, 'r');
            assert_int_equal(reason, FW_REASON_INCOMPLETE);
            assert_true(R.plant.pulses == pulses);
            ++refused;
            continue;
        }
        want[0] = m.v[1] * 1e-6;
        want[1] = m.v[2] * 1e-6;
        if (a == 'r') {
            assert_int_equal(reason, FW_REASON_KINEMATICS); /* the changed pose is out of reach */
            ++refused;
            continue;
        }
        assert_int_equal(a, 'a');
        lands_on(want); /* where the corrupted frame said, not where the host meant */
        ++elsewhere;
    }
    print_message("payload corrupted 8 times: %u refused, %u moved the plate where the corrupted frame said\n",
                  refused, elsewhere);
    assert_true(elsewhere > 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_dropped),
        cmocka_unit_test(test_duplicated),
        cmocka_unit_test(test_reordered),
        cmocka_unit_test(test_delayed),
        cmocka_unit_test(test_corrupted_length),
        cmocka_unit_test(test_corrupted_identifier),
        cmocka_unit_test(test_corrupted_payload),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
