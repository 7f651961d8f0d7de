/* The soak: a random host (valid commands for the state it sees, and invalid ones of every kind)
 * against the controller, the fault layer and the real plant on the fake clock, with random
 * faults throughout: frames to the controller dropped, duplicated, reordered, delayed and
 * corrupted; host silences; bus-off (some shorter than a control period); the e-stop opened; limit
 * switches tripped; missed steps.  At least 10,000 commands; the rig checks its invariants after
 * every control period (sim_rig.h) and fails at the first breach.
 *
 * Every frame that reaches the controller (that the fault layer hands over: a dropped frame never
 * does, a duplicated one does twice and each copy is a command of its own, a corrupted one does
 * as its corrupted bytes) is judged by docs/protocol.md, from its bytes and the state it met:
 *   - for another node, the broadcast node, or a controller-to-host function: no ACK or REJECT;
 *   - to this node, an unknown function: one REJECT unknown; a wrong length: one REJECT
 *     bad_length; a well-formed heartbeat: none; a pose part: none, or one REJECT; anything
 *     else: exactly one ACK or REJECT;
 *   - the answer names the frame's function, and its sequence number (0 for a wrong length, an
 *     unknown function, or a message without one; for a field out of range, its own or 0); a
 *     command the state table refuses is refused for the state (or for a field's range);
 *   - nothing of a refused or unanswered frame is applied (state, fault, homed, drives), and an
 *     accepted ENABLE, DISABLE, HOME, CLEAR_FAULT, MOVE_COMMIT or ESTOP has its effect.
 * Answers are attributed exactly: the controller answers within its handling of a frame, so the
 * ACKs and REJECTs it sends between one hand-over and the next (or the poll's end) are that
 * frame's; one sent outside any frame is an error.
 *
 * The host numbers its poses as tsectl does, one past the last accepted commit, and corruption
 * and random bytes may leave pose parts under any number: since a part of another number starts
 * the staging afresh, a stray part ahead of the host's numbers costs at most one incomplete
 * commit (it locked the host out for good before; docs/reliability.md), which the final move
 * checks.  Other commands take numbers from a counter of their own.
 *
 * The plant is a fixed machine built from the default parameters, so the host never changes a
 * physical parameter, corruption spares PARAM_SET frames (a corrupted but valid write would set
 * the controller up for another machine: test_fault_frames shows a corrupted valid command is
 * taken), and the soak fails if one changes anyway.  Missed steps are capped at 2000 a slide
 * between homings (1.6 mm, inside the plant's 10 mm overtravel).  A homing switch is forced only
 * outside homing (pressed during homing it would misplace the zero: undetectable, see
 * docs/reliability.md).
 *
 * At the end the faults stop, a well-behaved host clears, homes and moves, and the state must be
 * consistent: idle, no fault, homed, the counts the plant's true steps, the plate on its target,
 * STATUS saying so, nothing held or unread, the frame counts adding up.
 *
 * TSE_SOAK_SEED and TSE_SOAK_COMMANDS (default 10000) change the run. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "sim_rig.h"

#define FN(m) (proto_table[m].function)
#define NODE 1u
#define MISS_CAP 2000 /* steps a slide may miss between homings */

static sim_rig R;
static fault_rng rng;
static bool trace; /* TSE_SOAK_TRACE: a line per state change and command */

static uint32_t below(uint32_t n)
{
    return fault_rng_below(&rng, n);
}

static bool chance(double p)
{
    return fault_rng_unit(&rng) < p;
}

static double uniform(double a, double b)
{
    return a + (b - a) * fault_rng_unit(&rng);
}

static uint64_t now(void)
{
    return fault_clock_us(&R.can.clock);
}

/* docs/protocol.md, "Which command each state accepts": boot, disabled, homing, idle, moving,
 * stopping, fault, estop. */
static const char *const accepts[PM_COUNT] = {
    [PM_ESTOP] = "AAAAAAAA",       [PM_STOP] = "-AAAAAAA",        [PM_HOST_HEARTBEAT] = "AAAAAAAA",
    [PM_ENABLE] = "-A------",      [PM_DISABLE] = "-A-A--AA",     [PM_HOME] = "---A----",
    [PM_CLEAR_FAULT] = "------AA", [PM_POSE_A] = "-AAAAAAA",      [PM_POSE_B] = "-AAAAAAA",
    [PM_POSE_C] = "-AAAAAAA",      [PM_MOVE_COMMIT] = "---AA---", [PM_TRAJ_COMMIT] = "---AA---",
    [PM_PARAM_GET] = "AAAAAAAA",   [PM_PARAM_SET] = "-A----AA",   [PM_PARAM_SAVE] = "-A----AA",
    [PM_INFO_GET] = "AAAAAAAA",
    [PM_BOOT_ENTER] = "AA----AA",  [PM_BOOT_QUERY] = "--------",  [PM_BOOT_ERASE] = "--------",
    [PM_BOOT_WRITE] = "--------",  [PM_BOOT_VERIFY] = "--------", [PM_BOOT_START] = "--------",
    [PM_BOOT_DATA] = "--------",
};

/* What the host sends, by kind. */
typedef enum {
    K_ENABLE, K_DISABLE, K_HOME, K_STOP, K_ESTOP, K_CLEAR_FAULT, K_POSE_PART, K_MOVE_COMMIT, K_TRAJ_COMMIT,
    K_PARAM_GET, K_PARAM_SET, K_PARAM_SAVE, K_BAD_LENGTH, K_OUT_OF_RANGE, K_UNKNOWN_FUNCTION, K_STALE,
    K_OTHER_NODE, K_BROADCAST, K_HOST_BOUND, K_GARBAGE, K_KINDS
} host_kind;

static const char *const kind_names[K_KINDS] = {
    "enable", "disable", "home", "stop", "estop", "clear_fault", "pose part", "move commit", "traj commit",
    "param get", "param set", "param save", "wrong length", "field out of range", "unknown function",
    "stale sequence number", "to another node", "broadcast stop", "a controller-to-host function", "random bytes",
};

enum { W_SILENCE, W_SILENCE_PAST_WD, W_BUS_OFF, W_BUS_OFF_BETWEEN, W_ESTOP, W_LIMIT_HIGH, W_LIMIT_LOW, W_MISS, W_KINDS };
static const char *const window_names[W_KINDS] = {
    "host silences", "of them past the watchdog", "bus-offs", "of them between two looks", "e-stops opened",
    "high-end switches tripped", "homing switches forced", "missed-step bursts",
};

static struct {
    uint32_t sent, by_kind[K_KINDS], heartbeats, needing_answer, by_state[FW_STATE_COUNT];
    uint32_t delivered, answered, acks, rejects, ack_by_fn[128], reject_by_reason[FW_REASON_COUNT];
    uint32_t lost, duplicated, unsolicited, errors;
    uint32_t windows[W_KINDS], missed_steps;
    uint32_t faults[FW_FAULT_COUNT];
    uint32_t state_entries[FW_STATE_COUNT];
} n;

/* ---- the judge: every frame handed to the controller, by its bytes and the state it met ---- */

static struct {
    bool open;
    hal_can_frame f;
    fw_state state;
    fw_fault fault;
    bool homed, drives;
    unsigned answers;
    hal_can_frame first;
} cur;

static void error(const char *fmt, ...)
{
    ++n.errors;
    if (n.errors > 10)
        return;
    char buf[256];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    print_message("t = %.3f s: frame id 0x%03x len %u in state %d: %s\n", (double)now() * 1e-6, cur.f.id, cur.f.len,
                  cur.state, buf);
}

static bool has_seq(const proto_def *d)
{
    return d->nfields > 0 && strcmp(d->fields[0].name, "seq") == 0;
}

static void judge(void)
{
    if (!cur.open)
        return;
    cur.open = false;
    ++n.delivered;
    const fw_inspection now_in = rig_now(&R), *c = &now_in;
    const hal_can_frame *f = &cur.f;
    const uint8_t node = (uint8_t)(f->id & PROTO_NODE_MASK), fn = (uint8_t)(f->id >> PROTO_NODE_BITS);
    const proto_def *d = proto_lookup(fn, PROTO_TO_CONTROLLER);
    unsigned lo = 1, hi = 1;       /* answers expected */
    fw_reason must = FW_REASON_NONE; /* the REJECT's reason, if only one will do */
    bool pose = false;
    if (node != NODE || (!d && proto_lookup(fn, PROTO_TO_HOST)))
        lo = hi = 0;
    else if (!d)
        must = FW_REASON_UNKNOWN;
    else if (f->len != d->dlc)
        must = FW_REASON_BAD_LENGTH;
    else if (d->msg == PM_HOST_HEARTBEAT)
        lo = hi = 0;
    else if (d->msg >= PM_POSE_A && d->msg <= PM_POSE_C)
        lo = 0, pose = true;
    if (lo == 1)
        ++n.needing_answer;
    if (cur.answers < lo) {
        ++n.lost;
        error("no answer");
    } else if (cur.answers > hi) {
        if (hi == 1)
            ++n.duplicated;
        error("%u answers, at most %u due", cur.answers, hi);
    }
    const bool changed = c->state != cur.state || c->fault != cur.fault || c->homed != cur.homed ||
                         c->drives_on != cur.drives;
    if (cur.answers == 0) {
        if (changed && node != PROTO_BROADCAST)
            error("unanswered, yet state %d -> %d, fault %d -> %d", cur.state, c->state, cur.fault, c->fault);
        return;
    }
    ++n.answered;
    const hal_can_frame *a = &cur.first;
    const bool ack = (a->id >> PROTO_NODE_BITS) == FN(PM_ACK);
    const uint8_t reason = ack ? 0 : a->data[2];
    if (a->data[0] != fn)
        error("answer names function 0x%02x", a->data[0]);
    /* A frame refused for its length or function has no sequence number; one refused for a
     * field's range has its own byte, which the answer carries or leaves 0. */
    const bool unnumbered = reason == FW_REASON_UNKNOWN || reason == FW_REASON_BAD_LENGTH;
    const uint8_t seq = d && has_seq(d) && !unnumbered ? f->data[0] : 0;
    if (a->data[1] != seq && !(reason == FW_REASON_RANGE && a->data[1] == 0))
        error("answer (%s %u) carries sequence number %u, not %u", ack ? "ACK" : "REJECT", reason, a->data[1], seq);
    if (must != FW_REASON_NONE && (ack || reason != must))
        error("%s %u, not REJECT %u", ack ? "ACK" : "REJECT", reason, must);
    if (ack && pose)
        error("a pose part acknowledged");
    /* A row of a trajectory that has ended is refused as such whatever the state. */
    if (d && must == FW_REASON_NONE && accepts[d->msg][cur.state] == '-' &&
        (ack || (reason != FW_REASON_STATE && reason != FW_REASON_RANGE &&
                 !(d->msg == PM_TRAJ_COMMIT && reason == FW_REASON_ENDED))))
        error("refused by the state table, answered %s %u", ack ? "ACK" : "REJECT", reason);
    if (ack) {
        ++n.acks;
        ++n.ack_by_fn[fn & 0x7F];
        const proto_msg m = d ? d->msg : PM_COUNT;
        const bool ok = m == PM_ESTOP          ? c->state == FW_STATE_ESTOP
                        : m == PM_CLEAR_FAULT  ? c->state == FW_STATE_DISABLED && c->fault == FW_FAULT_NONE
                        : m == PM_ENABLE       ? c->state == FW_STATE_IDLE && c->drives_on
                        : m == PM_DISABLE      ? !c->drives_on && c->state != FW_STATE_IDLE
                        : m == PM_HOME         ? c->state == FW_STATE_HOMING
                        : m == PM_MOVE_COMMIT  ? c->state == FW_STATE_MOVING
                                               : true;
        if (!ok)
            error("acknowledged, but now state %d, fault %d, drives %d", c->state, c->fault, c->drives_on);
    } else {
        ++n.rejects;
        ++n.reject_by_reason[reason < FW_REASON_COUNT ? reason : 0];
        if (changed)
            error("refused (reason %u), yet state %d -> %d, fault %d -> %d, homed %d -> %d", reason, cur.state,
                  c->state, cur.fault, c->fault, cur.homed, c->homed);
    }
}

/* The frame whose handling begins now: the state it meets. */
static void begin(const hal_can_frame *f)
{
    judge();
    cur.open = true;
    cur.f = *f;
    cur.state = fw_state_of(R.fw);
    cur.fault = fw_fault_of(R.fw);
    cur.homed = fw_homed_of(R.fw);
    cur.drives = fw_drives_of(R.fw);
    cur.answers = 0;
}

/* While a commit is validated the controller reads the bus ahead (fw/work.h: heartbeats taken, a
 * STOP seen) and handles what it read after the commit, in order; so it does while any command
 * waits for the control tick to take it (fw/runtime.h), which on the board's timing (the *_board
 * build) is a wait of up to a control period.  Those frames wait here: the handling of the next
 * begins once the one before has been answered, or has been passed by an answer naming another
 * function, or at the end of the poll. */
#define AHEAD 64u
static struct {
    hal_can_frame f[AHEAD];
    unsigned head, count;
} ahead;

static bool validating(void)
{
    if (!cur.open || cur.answers > 0 || (cur.f.id & PROTO_NODE_MASK) != NODE)
        return false;
    const proto_def *d = proto_lookup((uint8_t)(cur.f.id >> PROTO_NODE_BITS), PROTO_TO_CONTROLLER);
#if SIM_RIG_BOARD_TIME
    /* Any command that is answered: it may wait for the tick. */
    return d && cur.f.len == d->dlc && d->msg != PM_HOST_HEARTBEAT && d->msg != PM_POSE_A && d->msg != PM_POSE_B &&
           d->msg != PM_POSE_C;
#else
    return d && cur.f.len == d->dlc && (d->msg == PM_MOVE_COMMIT || d->msg == PM_TRAJ_COMMIT);
#endif
}

static void next_ahead(void)
{
    begin(&ahead.f[ahead.head]);
    ahead.head = (ahead.head + 1u) % AHEAD;
    --ahead.count;
}

static void tap(void *arg, fault_can_tap what, const hal_can_frame *f)
{
    (void)arg;
    if (what == FAULT_TAP_DELIVERED) {
        if (ahead.count > 0 || validating()) {
            assert_true(ahead.count < AHEAD);
            ahead.f[(ahead.head + ahead.count++) % AHEAD] = *f;
        } else {
            begin(f);
        }
        return;
    }
    const uint8_t fn = (uint8_t)(f->id >> PROTO_NODE_BITS);
    if (fn != FN(PM_ACK) && fn != FN(PM_REJECT))
        return;
    while (ahead.count > 0 && (!cur.open || cur.answers > 0 || f->data[0] != (uint8_t)(cur.f.id >> PROTO_NODE_BITS)))
        next_ahead();
    if (!cur.open) {
        ++n.unsolicited;
        error("an answer outside any frame's handling");
        return;
    }
    if (cur.answers++ == 0)
        cur.first = *f;
}

static void after_poll(void *arg)
{
    (void)arg;
    while (ahead.count > 0)
        next_ahead();
    judge();
}

/* Corruptions the soak does not make (see the top): any that touches a parameter write. */
static bool spare(void *arg, const hal_can_frame *before, const hal_can_frame *after)
{
    (void)arg;
    return (before->id >> PROTO_NODE_BITS) == FN(PM_PARAM_SET) || (after->id >> PROTO_NODE_BITS) == FN(PM_PARAM_SET);
}

/* ---- the host ---- */

static struct {
    uint8_t seq;
    uint32_t wait;          /* ms to the next command */
    int traj_left;          /* trajectory points still to stream */
    uint8_t traj_id;        /* the stream's identity: its first row's number */
    uint32_t traj_wait;
    double traj_pose[6];
} host;

static void frame(host_kind k, uint16_t id, uint8_t len, const uint8_t *d)
{
    fake_send(&R.bus, id, len, d);
    ++n.by_state[fw_state_of(R.fw)];
    ++n.sent;
    ++n.by_kind[k];
}

static void msg_to(host_kind k, uint8_t node, proto_msg m, const int32_t *v)
{
    hal_can_frame f;
    assert_int_equal(proto_encode_values(m, node, v, &f), 0);
    frame(k, f.id, f.len, f.data);
}

static void msg(host_kind k, proto_msg m, const int32_t *v)
{
    msg_to(k, NODE, m, v);
}

static void simple(host_kind k, proto_msg m)
{
    const int32_t v[1] = {host.seq++};
    msg(k, m, v);
}

static void random_pose(double p[6])
{
    p[0] = uniform(-0.12, 0.12);
    p[1] = uniform(-0.12, 0.12);
    p[2] = uniform(0.85, 1.35);
    p[3] = uniform(-0.1, 0.1);
    p[4] = uniform(-0.1, 0.1);
    p[5] = uniform(-0.3, 0.3);
}

static void parts(uint8_t s, const double p[6])
{
    for (int i = 0; i < 3; ++i) {
        const int32_t v[3] = {s, (int32_t)lround(p[2 * i] * 1e6), (int32_t)lround(p[2 * i + 1] * 1e6)};
        msg(K_POSE_PART, (proto_msg)(PM_POSE_A + i), v);
    }
}

/* A pose's number, as tsectl takes it: one past the last accepted commit (STATUS.last_seq). */
static uint8_t pose_seq(void)
{
    return (uint8_t)(rig_now(&R).last_seq + 1);
}

static void move(void)
{
    const uint8_t s = pose_seq();
    double p[6];
    random_pose(p);
    parts(s, p);
    const bool by_time = chance(0.7);
    const int32_t v[3] = {s, by_time ? 0 : 1, by_time ? (int32_t)(300 + below(2700)) : (int32_t)(20000 + below(280000))};
    msg(K_MOVE_COMMIT, PM_MOVE_COMMIT, v);
}

static void traj_point(bool first)
{
    const uint8_t s = pose_seq();
    for (int k = 0; k < 6; ++k)
        host.traj_pose[k] += k < 3 ? uniform(-0.002, 0.002) : uniform(-0.004, 0.004);
    parts(s, host.traj_pose);
    --host.traj_left;
    /* Most streams end with a last point; the others run dry (an underrun). */
    const int32_t last = host.traj_left == 0 && chance(0.8);
    const int32_t flags = (first ? (int32_t)PROTO_TRAJ_FIRST : 0) | (last ? (int32_t)PROTO_TRAJ_LAST : 0);
    const int32_t v[4] = {s, first ? (int32_t)(200000 + below(300000)) : (int32_t)(20000 + below(60000)), flags,
                          host.traj_id};
    msg(K_TRAJ_COMMIT, PM_TRAJ_COMMIT, v);
}

static void traj_start(void)
{
    host.traj_left = 3 + (int)below(28);
    for (int k = 0; k < 6; ++k)
        host.traj_pose[k] = (double)rig_now(&R).pose[k];
    host.traj_id = pose_seq();
    traj_point(true);
    host.traj_wait = 10 + below(30);
}

static void param_get(void)
{
    const int32_t v[1] = {(int32_t)below(FP_COUNT + 6)}; /* a few unknown ids */
    msg(K_PARAM_GET, PM_PARAM_GET, v);
}

/* Writes that leave the machine the plant is: timing of the bus and the homing speed; a physical
 * parameter only to its present value; and refusals (out of range, unknown). */
static void param_set(void)
{
    int32_t id, value;
    switch (below(6)) {
    case 0: id = FP_STATUS_MS, value = 20 + (int32_t)below(480); break;
    case 1: id = FP_TELEMETRY_MS, value = (int32_t)below(200); break;
    case 2: id = FP_WATCHDOG_MS, value = 200 + (int32_t)below(1800); break;
    case 3: id = FP_HOMING_SPEED, value = 10000 + (int32_t)below(20000); break;
    case 4: id = (int32_t)below(FP_COUNT), value = fw_params_of(R.fw)->v[id]; break;
    default: id = FP_SLIDE_VMAX, value = 0; break; /* below its range */
    }
    if (chance(0.1))
        id = FP_COUNT + (int32_t)below(1000); /* unknown */
    const int32_t v[2] = {id, value};
    msg(K_PARAM_SET, PM_PARAM_SET, v);
}

static void param_save(void)
{
    const int32_t v[1] = {0x45564153};
    msg(K_PARAM_SAVE, PM_PARAM_SAVE, v);
}

static proto_msg any_command(void)
{
    proto_msg m;
    do
        m = (proto_msg)below(PM_COUNT);
    while (proto_table[m].dir != PROTO_TO_CONTROLLER);
    return m;
}

static void invalid(void)
{
    uint8_t d[8];
    for (int b = 0; b < 8; ++b)
        d[b] = (uint8_t)below(256);
    /* Broadcast stops are rare: each stops whatever runs. */
    const uint32_t pick = below(301);
    switch (pick == 300 ? 5 : pick % 7 < 5 ? pick % 7 : pick % 7 + 1) {
    case 0: { /* a command of a wrong length */
        const proto_msg m = any_command();
        uint8_t len;
        do
            len = (uint8_t)below(9);
        while (len == proto_table[m].dlc);
        frame(K_BAD_LENGTH, proto_id(m, NODE), len, d);
        break;
    }
    case 1: { /* a field out of its range */
        const uint8_t s = host.seq++;
        const uint32_t which = below(4);
        uint8_t f[8] = {s, 0, 0, 0, 0, 0, 0, 0};
        if (which == 0) {
            f[1] = (uint8_t)(2 + below(254)); /* MOVE_COMMIT kind */
            f[2] = 100;
            frame(K_OUT_OF_RANGE, proto_id(PM_MOVE_COMMIT, NODE), proto_table[PM_MOVE_COMMIT].dlc, f);
        } else if (which == 1) {
            f[1] = (uint8_t)below(200); /* TRAJ_COMMIT dt below 1 ms */
            frame(K_OUT_OF_RANGE, proto_id(PM_TRAJ_COMMIT, NODE), proto_table[PM_TRAJ_COMMIT].dlc, f);
        } else if (which == 2) {
            f[1] = 0xFF, f[2] = 0xFF, f[3] = 0x7F; /* POSE_B z = 8.39 m */
            frame(K_OUT_OF_RANGE, proto_id(PM_POSE_B, NODE), proto_table[PM_POSE_B].dlc, f);
        } else {
            f[0] = 'X'; /* PARAM_SAVE without its magic */
            frame(K_OUT_OF_RANGE, proto_id(PM_PARAM_SAVE, NODE), proto_table[PM_PARAM_SAVE].dlc, f);
        }
        break;
    }
    case 2: { /* a function no one has */
        uint8_t fn;
        do
            fn = (uint8_t)below(128);
        while (proto_lookup(fn, PROTO_TO_CONTROLLER) || proto_lookup(fn, PROTO_TO_HOST));
        frame(K_UNKNOWN_FUNCTION, (uint16_t)(fn << PROTO_NODE_BITS | NODE), (uint8_t)below(9), d);
        break;
    }
    case 3: { /* an old sequence number: the last accepted commit's, or one before it */
        const uint8_t s = (uint8_t)(rig_now(&R).last_seq - below(100));
        if (chance(0.5)) {
            const int32_t v[3] = {s, 0, 1000};
            msg(K_STALE, PM_MOVE_COMMIT, v);
        } else {
            const int32_t v[3] = {s, 0, 1000000};
            msg(K_STALE, PM_POSE_B, v);
        }
        break;
    }
    case 4: { /* a valid command for another controller */
        const int32_t v[3] = {host.seq++, 0, 0};
        const proto_msg m = chance(0.5) ? PM_HOME : PM_ENABLE;
        msg_to(K_OTHER_NODE, (uint8_t)(2 + below(14)), m, v);
        break;
    }
    case 5: { /* every controller: stop (rarely, e-stop) */
        const int32_t v[1] = {host.seq++};
        msg_to(K_BROADCAST, PROTO_BROADCAST, chance(0.05) ? PM_ESTOP : PM_STOP, v);
        break;
    }
    case 6: { /* a controller's own kind of frame */
        const proto_msg m = (proto_msg)(PM_STATUS + below(PM_COUNT - PM_STATUS));
        frame(K_HOST_BOUND, proto_id(m, NODE), proto_table[m].dlc, d);
        break;
    }
    default: { /* random bytes, except a parameter write (see the top) */
        uint16_t id;
        uint8_t len;
        do {
            id = (uint16_t)below(0x800);
            len = (uint8_t)below(9);
        } while ((id >> PROTO_NODE_BITS) == FN(PM_PARAM_SET));
        frame(K_GARBAGE, id, len, d);
        break;
    }
    }
}

/* What a host that knows the state sends, in parts per 10000.  Homing takes seconds and a move
 * up to a few, with a command every 20 ms on average: stops and e-stops are rare enough that
 * most homings and moves run to their end. */
static void valid(void)
{
    const uint32_t r = below(10000);
    switch (fw_state_of(R.fw)) {
    case FW_STATE_DISABLED:
        if (r < 5500)
            simple(K_ENABLE, PM_ENABLE);
        else if (r < 7000)
            param_get();
        else if (r < 8200)
            param_set();
        else if (r < 8600)
            param_save();
        else if (r < 9300)
            simple(K_HOME, PM_HOME);
        else
            simple(K_CLEAR_FAULT, PM_CLEAR_FAULT);
        break;
    case FW_STATE_IDLE:
        if (!fw_homed_of(R.fw)) {
            if (r < 6000)
                simple(K_HOME, PM_HOME);
            else if (r < 6500)
                simple(K_DISABLE, PM_DISABLE);
            else if (r < 8000)
                param_get();
            else if (r < 9000)
                move();
            else
                simple(K_STOP, PM_STOP);
        } else if (r < 3500) {
            move();
        } else if (r < 6500) {
            traj_start();
        } else if (r < 6700) {
            simple(K_DISABLE, PM_DISABLE);
        } else if (r < 6900) {
            simple(K_HOME, PM_HOME);
        } else if (r < 7400) {
            simple(K_STOP, PM_STOP);
        } else if (r < 9800) {
            param_get();
        } else if (r < 9950) {
            param_set();
        } else {
            simple(K_ESTOP, PM_ESTOP);
        }
        break;
    case FW_STATE_MOVING:
        if (r < 600)
            move();
        else if (r < 630)
            simple(K_STOP, PM_STOP);
        else if (r < 9790)
            param_get();
        else if (r < 9990)
            simple(K_DISABLE, PM_DISABLE);
        else
            simple(K_ESTOP, PM_ESTOP);
        break;
    case FW_STATE_FAULT:
    case FW_STATE_ESTOP:
        if (r < 6000)
            simple(K_CLEAR_FAULT, PM_CLEAR_FAULT);
        else if (r < 7000)
            simple(K_DISABLE, PM_DISABLE);
        else if (r < 8000)
            param_get();
        else if (r < 8800)
            param_set();
        else if (r < 9400)
            simple(K_ENABLE, PM_ENABLE);
        else
            simple(K_STOP, PM_STOP);
        break;
    default: /* homing, stopping: the host mostly waits */
        if (r < 8000)
            param_get();
        else if (r < 9000)
            move();
        else if (r < 9900)
            simple(K_ENABLE, PM_ENABLE);
        else if (r < 9993)
            simple(K_HOME, PM_HOME);
        else if (r < 9998)
            simple(K_STOP, PM_STOP);
        else
            simple(K_ESTOP, PM_ESTOP);
        break;
    }
}

static void host_ms(void)
{
    if (R.ticks % 10 == 0) {
        const int32_t v[1] = {(int32_t)(R.ticks / 10 % 256)};
        rig_send(&R, PM_HOST_HEARTBEAT, v);
        ++n.heartbeats;
    }
    if (host.traj_left > 0 && --host.traj_wait == 0) {
        traj_point(false);
        host.traj_wait = 10 + below(30);
    }
    if (host.wait > 0) {
        --host.wait;
        return;
    }
    /* A command every 20 ms on average; while homing, which takes seconds, every 50 ms. */
    host.wait = below(fw_state_of(R.fw) == FW_STATE_HOMING ? 100 : 40);
    if (chance(0.2))
        invalid();
    else
        valid();
}

/* ---- the faults ---- */

static int64_t miss_base[6]; /* stepper.lost at the last homing's end */

static bool open_window(const fault_window *w, uint64_t t)
{
    return !fault_window_empty(w) && t < w->until_us;
}

/* Each kind of fault window at random, and at least once every two minutes (so that a run of any
 * seed has them all). */
static uint64_t last_start[W_KINDS];

static bool due(int w, double p, uint64_t t)
{
    return chance(p) || t >= last_start[w] + 120000000u;
}

static void started(int w, uint64_t t)
{
    ++n.windows[w];
    last_start[w] = t;
}

static void faults_ms(void)
{
    const uint64_t t = now();
    fault_can_config *cc = &R.can.cfg;
    fault_inputs_config *ic = &R.inputs.cfg;
    const uint32_t wd = (uint32_t)fw_params_of(R.fw)->v[FP_WATCHDOG_MS];
    if (!open_window(&cc->silence, t) && due(W_SILENCE, 1.0 / 60000, t)) {
        const bool past = chance(0.5) || (n.windows[W_SILENCE_PAST_WD] == 0 && n.windows[W_SILENCE] % 2 == 1);
        const uint32_t ms = past ? wd + 10 + below(1000) : 50 + below(wd - 70);
        cc->silence = (fault_window){t, t + 1000u * ms};
        started(W_SILENCE, t);
        if (past)
            started(W_SILENCE_PAST_WD, t);
    }
    if (!open_window(&cc->bus_off, t) && due(W_BUS_OFF, 1.0 / 100000, t)) {
        if (chance(0.3) || (n.windows[W_BUS_OFF_BETWEEN] == 0 && n.windows[W_BUS_OFF] % 2 == 1)) {
            /* begun and ended between two control ticks' looks */
            const uint64_t from = t + 100 + below(400);
            cc->bus_off = (fault_window){from, from + 100 + below(400)};
            started(W_BUS_OFF_BETWEEN, t);
        } else {
            cc->bus_off = (fault_window){t, t + 1000u * (1 + below(200))};
        }
        started(W_BUS_OFF, t);
    }
    if (!open_window(&ic->estop, t) && due(W_ESTOP, 1.0 / 100000, t)) {
        const uint64_t from = t + below(1000);
        ic->estop = (fault_window){from, from + 1000u * (20 + below(580))};
        started(W_ESTOP, t);
    }
    /* A homing switch only outside homing (see the top), a high-end one at any time. */
    const bool homing = fw_state_of(R.fw) == FW_STATE_HOMING;
    const bool low = !homing && n.windows[W_LIMIT_LOW] <= n.windows[W_LIMIT_HIGH];
    if (!open_window(&ic->limit, t) && due(low ? W_LIMIT_LOW : W_LIMIT_HIGH, 1.0 / 40000, t)) {
        const uint32_t k = below(6);
        ic->limit_mask = (uint16_t)(1u << (low ? k : 8 + k));
        ic->limit = (fault_window){t, t + 1000u * (5 + below(295))};
        started(low ? W_LIMIT_LOW : W_LIMIT_HIGH, t);
    }
    if (homing && (ic->limit_mask & 0x3F) && open_window(&ic->limit, t))
        ic->limit.until_us = t;
    if (chance(1.0 / 500)) {
        const uint32_t k = below(6);
        const int64_t drift = R.stepper.lost[k] - miss_base[k];
        if (drift < MISS_CAP && drift > -MISS_CAP) {
            const uint32_t m = 1 + below(2);
            R.stepper.cfg.miss[k] += m;
            n.missed_steps += m;
            started(W_MISS, t);
        }
    }
}

/* The physical parameters, which must stay the plant's. */
static bool physical(int id)
{
    return id <= FP_S_MAX || id == FP_STEPS_PER_M || id == FP_SLIDE_VMAX || id == FP_SLIDE_AMAX ||
           id == FP_STEP_RATE_MAX || (id >= FP_HOME_SW_1 && id <= FP_HOME_SW_6) || id == FP_STEP_PULSE_NS ||
           id == FP_DIR_SETUP_NS;
}

static fw_param_set machine;

static void after_tick(fw_state before)
{
    const fw_inspection now_in = rig_now(&R), *c = &now_in;
    for (int id = 0; id < FP_COUNT; ++id)
        if (physical(id) && c->params.v[id] != machine.v[id])
            fail_msg("t = %.3f s: parameter %d changed from %d to %d: the soak's own error (see the top)",
                     (double)now() * 1e-6, id, machine.v[id], c->params.v[id]);
    if (c->state == before)
        return;
    ++n.state_entries[c->state];
    if (c->state == FW_STATE_FAULT || c->state == FW_STATE_ESTOP)
        ++n.faults[c->fault];
    if (before == FW_STATE_HOMING && c->state == FW_STATE_IDLE && c->homed)
        memcpy(miss_base, R.stepper.lost, sizeof miss_base);
    /* Faults with no cause the soak injects: the controller's own defects. */
    if (c->fault == FW_FAULT_PLANNER || c->fault == FW_FAULT_STEP_OVERRUN || c->fault == FW_FAULT_PLANT ||
        c->fault == FW_FAULT_HARDWARE)
        fail_msg("t = %.3f s: fault %d", (double)now() * 1e-6, c->fault);
}

static void period(void)
{
    faults_ms();
    const uint32_t sent = n.sent;
    host_ms();
    const fw_state before = fw_state_of(R.fw);
    rig_tick(&R);
    after_tick(before);
    if (trace && before == FW_STATE_MOVING && fw_state_of(R.fw) == FW_STATE_STOPPING)
        print_message("t %.3f stop: source %d at %.4f of %.4f s (ramps %.4f s), blend %d from segment %u, stop ramp %.4f s\n",
                      (double)now() * 1e-6, rig_now(&R).src, (double)rig_now(&R).tau, (double)rig_now(&R).move.prof.T, (double)rig_now(&R).move.prof.Ta,
                      rig_now(&R).has_next, rig_now(&R).blend_k0, (double)rig_now(&R).stop_T);
    if (trace && (fw_state_of(R.fw) != before || n.sent != sent))
        print_message("t %.3f state %d -> %d fault %d src %d stopping %d sent %u; windows: silence %d bus-off %d e-stop %d limit %d (0x%x); missed %u\n",
                      (double)now() * 1e-6, before, fw_state_of(R.fw), fw_fault_of(R.fw), rig_now(&R).src, rig_now(&R).stopping, n.sent,
                      open_window(&R.can.cfg.silence, now()), open_window(&R.can.cfg.bus_off, now()),
                      open_window(&R.inputs.cfg.estop, now()), open_window(&R.inputs.cfg.limit, now()), R.inputs.cfg.limit_mask,
                      n.missed_steps);
}

/* ---- the end: faults off, a well-behaved host ---- */

static void calm(uint32_t ms)
{
    for (uint32_t m = 0; m < ms; ++m) {
        const fw_state before = fw_state_of(R.fw);
        rig_run(&R, 1);
        after_tick(before);
    }
}

static char final_answer(unsigned from, proto_msg m, uint8_t s, uint8_t *reason)
{
    return rig_answer(&R, from, FN(m), s, reason);
}

static void settle(void)
{
    memset(&R.can.cfg.p, 0, sizeof R.can.cfg.p);
    R.can.cfg.silence = R.can.cfg.bus_off = (fault_window){0, 0};
    R.inputs.cfg.estop = R.inputs.cfg.limit = (fault_window){0, 0};
    memset(R.stepper.cfg.miss, 0, sizeof R.stepper.cfg.miss);
    host.traj_left = 0;
    calm(100); /* held frames come in */
    if (fw_state_of(R.fw) == FW_STATE_MOVING || fw_state_of(R.fw) == FW_STATE_STOPPING || fw_state_of(R.fw) == FW_STATE_HOMING) {
        R.seq = host.seq;
        rig_cmd(&R, PM_STOP);
        for (int t = 0; t < 60000 && (fw_state_of(R.fw) == FW_STATE_MOVING || fw_state_of(R.fw) == FW_STATE_STOPPING ||
                                      fw_state_of(R.fw) == FW_STATE_HOMING);
             ++t)
            calm(1);
    }
    R.seq = host.seq;
    if (fw_state_of(R.fw) == FW_STATE_FAULT || fw_state_of(R.fw) == FW_STATE_ESTOP) {
        rig_cmd(&R, PM_CLEAR_FAULT);
        calm(10);
    }
    if (fw_state_of(R.fw) == FW_STATE_IDLE) {
        rig_cmd(&R, PM_DISABLE);
        calm(10);
    }
    assert_int_equal(fw_state_of(R.fw), FW_STATE_DISABLED);
    rig_home(&R);
    static const double target[6] = {0.03, -0.02, 1.05, 0.02, 0.0, 0.05};
    const unsigned asked = R.nlog;
    R.seq = pose_seq();
    const uint8_t last = rig_move(&R, target, 1500);
    calm(10);
    uint8_t reason = 0;
    const char a = final_answer(asked, PM_MOVE_COMMIT, last, &reason);
    if (a != 'a')
        fail_msg("the final move: answer '%c', reason %u (staged %u, parts 0x%x, last accepted %u)", a ? a : '-',
                 reason, rig_now(&R).stage_seq, rig_now(&R).stage_have, rig_now(&R).last_seq);
    for (int t = 0; t < 30000 && fw_state_of(R.fw) != FW_STATE_IDLE; ++t)
        calm(1);
    const unsigned from = R.nlog;
    calm(1000); /* a STATUS comes at least every 0.5 s (the host sets status_ms up to 499) */
    /* Consistent: at rest, no fault, homed, the counts the truth, the plate on its target. */
    assert_int_equal(fw_state_of(R.fw), FW_STATE_IDLE);
    assert_int_equal(fw_fault_of(R.fw), FW_FAULT_NONE);
    assert_true(fw_homed_of(R.fw) && R.plant.enabled);
    for (int k = 0; k < 6; ++k)
        assert_true(llabs((long long)rig_count_error(&R, k)) <= 1);
    assert_true(rig_plate_at(&R, target));
    const proto_message st = rig_status(&R, from);
    assert_int_equal(st.v[0], FW_STATE_IDLE);
    assert_int_equal(st.v[1], FW_FAULT_NONE);
    assert_int_equal(st.v[2] & 0x0F, 3); /* homed, drives on, e-stop closed, switches agree */
    assert_int_equal(st.v[3], 0);        /* no trajectory queued */
    assert_int_equal(st.v[5], last);
    /* Nothing left on the bus or held; every frame accounted for. */
    const fault_can_stats *s = &R.can.stats;
    assert_int_equal(R.bus.rx_count, 0);
    assert_int_equal(R.can.nheld, 0);
    assert_int_equal(s->received + s->faults[FAULT_DUP],
                     s->delivered + s->faults[FAULT_DROP] + s->silenced + s->bus_off_lost);
    assert_int_equal(s->delivered, n.delivered);
}

static void report(void)
{
    const fault_can_stats *s = &R.can.stats;
    print_message("soak (controller in %s): %.1f s simulated, %llu control periods checked, plant invariant "
                  "breaches %s; in %llu of them moving, homed, no step lost: the true slides at a valid pose by "
                  "double FK\n",
                  TSE_REAL_FLOAT ? "float" : "double", (double)now() * 1e-6, (unsigned long long)R.ticks,
                  R.plant.breaches ? "SOME" : "0", (unsigned long long)R.poses_checked);
#if SIM_RIG_BOARD_TIME
    const double us = 1e6 / BT_HZ;
    print_message("board timing: the thread's longest work %.2f ms; control ticks lost %llu, the latest began %.1f us "
                  "behind its time; CPU %.1f %% thread, %.1f %% control, %.1f %% step\n",
                  (double)R.bt.thread_run_max * us * 1e-3, (unsigned long long)R.bt.control_lost,
                  (double)R.bt.control_late_max * us, 100.0 * (double)R.bt.charged[BT_THREAD] / (double)R.bt.now,
                  100.0 * (double)R.bt.charged[BT_CONTROL] / (double)R.bt.now,
                  100.0 * (double)R.bt.charged[BT_STEP] / (double)R.bt.now);
#endif
    print_message("commands sent: %u (and %u heartbeats); by kind:\n", n.sent, n.heartbeats);
    for (int k = 0; k < K_KINDS; ++k)
        print_message("  %-32s %u\n", kind_names[k], n.by_kind[k]);
    print_message("frames reaching the controller: %u, of which %u needed an answer; answered %u: %u ACK, %u REJECT; "
                  "lost answers %u, duplicated %u, unsolicited %u; judge errors in all %u\n",
                  n.delivered, n.needing_answer, n.answered, n.acks, n.rejects, n.lost, n.duplicated, n.unsolicited,
                  n.errors);
    print_message("accepted by function:");
    for (int fn = 0; fn < 128; ++fn)
        if (n.ack_by_fn[fn]) {
            const proto_def *d = proto_lookup((uint8_t)fn, PROTO_TO_CONTROLLER);
            print_message(" %s %u", d ? d->name : "?", n.ack_by_fn[fn]);
        }
    print_message("\nrejected by reason:");
    for (int r = 1; r < FW_REASON_COUNT; ++r)
        if (n.reject_by_reason[r])
            print_message(" %s %u", proto_enum_name(proto_reason_names, r), n.reject_by_reason[r]);
    print_message("\nframe faults: dropped %u, duplicated %u, reordered %u, delayed %u, corrupted %u (payload %u, length "
                  "%u, identifier %u; %u parameter writes spared), lost to silence %u, lost while bus-off %u, sends "
                  "refused while bus-off %u\n",
                  s->faults[FAULT_DROP], s->faults[FAULT_DUP], s->faults[FAULT_REORDER], s->faults[FAULT_DELAY],
                  s->faults[FAULT_CORRUPT], s->corrupt_payload, s->corrupt_length, s->corrupt_id, s->spared, s->silenced,
                  s->bus_off_lost, s->send_refused);
    print_message("other faults:");
    for (int w = 0; w < W_KINDS; ++w)
        print_message(" %s %u;", window_names[w], n.windows[w]);
    print_message(" steps missed %u\n", n.missed_steps);
    print_message("commands sent in state:");
    for (int st = 1; st < FW_STATE_COUNT; ++st)
        print_message(" %s %u", proto_enum_name(proto_state_names, st), n.by_state[st]);
    print_message("\nstates entered:");
    for (int st = 1; st < FW_STATE_COUNT; ++st)
        print_message(" %s %u (%.1f s)", proto_enum_name(proto_state_names, st), n.state_entries[st],
                      R.state_ms[st] * 1e-3);
    print_message("\nfaults latched:");
    for (int f = 1; f < FW_FAULT_COUNT; ++f)
        if (n.faults[f])
            print_message(" %s %u", proto_enum_name(proto_fault_names, f), n.faults[f]);
    print_message("\n");
}

static uint64_t env_number(const char *name, uint64_t fallback)
{
    const char *v = getenv(name);
    return v && *v ? strtoull(v, NULL, 10) : fallback;
}

static void test_soak(void **state)
{
    (void)state;
    const uint64_t seed = env_number("TSE_SOAK_SEED", 20240917);
    const uint64_t commands = env_number("TSE_SOAK_COMMANDS", 10000);
    trace = getenv("TSE_SOAK_TRACE") != NULL;
    print_message("soak: seed %llu, at least %llu commands\n", (unsigned long long)seed, (unsigned long long)commands);
    fault_rng_seed(&rng, seed);
    memset(&n, 0, sizeof n);
    memset(&cur, 0, sizeof cur);
    memset(&host, 0, sizeof host);
    rig_boot(&R, 0.05);
    machine = (*fw_params_of(R.fw));
    memset(miss_base, 0, sizeof miss_base);
    memset(last_start, 0, sizeof last_start);
    R.host_alive = false; /* the soak's host sends its own heartbeats */
    R.after_poll = after_poll;
    fault_rng_seed(&R.can.rng, seed + 1);
    for (int k = 0; k < FAULT_CAN_KINDS; ++k)
        R.can.cfg.p[k] = 0.01;
    R.can.cfg.tap = tap;
    R.can.cfg.spare = spare;
    host.seq = 1;
    /* Commands that need an answer, not only frames, number at least `commands`. */
    while (n.sent < commands || n.needing_answer < commands) {
        period();
        if (R.ticks > 3600000u)
            fail_msg("an hour simulated and only %u commands", n.sent);
    }
    R.host_alive = true;
    settle();
    report();
    assert_int_equal(n.lost, 0);
    assert_int_equal(n.duplicated, 0);
    assert_int_equal(n.unsolicited, 0);
    assert_int_equal(n.errors, 0);
    /* The soak went where it should: every state, and every fault injected. */
    for (int st = FW_STATE_DISABLED; st < FW_STATE_COUNT; ++st)
        assert_true(n.state_entries[st] > 0);
    for (int k = 0; k < FAULT_CAN_KINDS; ++k)
        assert_true(R.can.stats.faults[k] > 0);
    for (int w = 0; w < W_KINDS; ++w)
        assert_true(n.windows[w] > 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_soak)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
