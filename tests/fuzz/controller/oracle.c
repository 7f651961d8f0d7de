#include "oracle.h"
#include "fk_check.h"
#include "oracle_model.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_target.h"
#include "plant_check.h"
#include "snapshot.h"
#include "summary.h"
#include "wire.h"

#define BIT(s) (1u << (s))

/* The transitions docs/controller.md ("How the state changes") and docs/protocol.md allow (bit
 * `to` of next_states[from]); an e-stop (command, input or interrupt) may come in any state after
 * boot.
 *  boot: enters disabled once initialised.
 *  disabled: ENABLE energises (idle); a bus-off or a fault the platform reports latches a fault
 *    (nothing moves, so there is no stop to run first).
 *  idle: DISABLE; HOME; a commit starts motion; a fault at rest latches at once.
 *  homing: ends idle (homed, or brought to rest by STOP); STOP or a fault brings it to rest along
 *    its ramps (stopping); a homing fault ramps down within homing and then latches.
 *  moving: ends idle; STOP or a fault brings it to rest (stopping); a fault raised as its last
 *    setpoints step out (or one that ends the motion, the planner's) latches once at rest.
 *  stopping: at rest it is idle, or the fault that asked for the stop.
 *  fault, estop: CLEAR_FAULT leaves them, with the drives off (disabled). */
static const uint8_t next_states[FW_STATE_COUNT] = {
    [FW_STATE_BOOT] = BIT(FW_STATE_DISABLED),
    [FW_STATE_DISABLED] = BIT(FW_STATE_IDLE) | BIT(FW_STATE_FAULT) | BIT(FW_STATE_ESTOP),
    [FW_STATE_HOMING] = BIT(FW_STATE_IDLE) | BIT(FW_STATE_STOPPING) | BIT(FW_STATE_FAULT) | BIT(FW_STATE_ESTOP),
    [FW_STATE_IDLE] = BIT(FW_STATE_DISABLED) | BIT(FW_STATE_HOMING) | BIT(FW_STATE_MOVING) |
                      BIT(FW_STATE_FAULT) | BIT(FW_STATE_ESTOP),
    [FW_STATE_MOVING] = BIT(FW_STATE_IDLE) | BIT(FW_STATE_STOPPING) | BIT(FW_STATE_FAULT) | BIT(FW_STATE_ESTOP),
    [FW_STATE_STOPPING] = BIT(FW_STATE_IDLE) | BIT(FW_STATE_FAULT) | BIT(FW_STATE_ESTOP),
    [FW_STATE_FAULT] = BIT(FW_STATE_DISABLED) | BIT(FW_STATE_ESTOP),
    [FW_STATE_ESTOP] = BIT(FW_STATE_DISABLED),
};

static oracle_model o;

static void suspect_zero(rig *r)
{
    o.zero_suspect |= (uint8_t)(r->f.forced_limits & 0x3Fu);
    plant_check_zero_suspect(o.zero_suspect);
}

/* TSE_FUZZ_TRACE=1: every frame fed (but heartbeats) and answered, and every state change, on
 * stderr; =2: the slides at every segment boundary of a motion too.  To read what an input does,
 * never while fuzzing. */
static int trace = -1;

static void trace_frame(const rig *r, const char *dir, const hal_can_frame *f)
{
    fprintf(stderr, "%9.3f ms %s %03x [%u]", (double)r->f.now_us / 1000.0, dir, (unsigned)f->id, f->len);
    for (unsigned i = 0; i < f->len && i < 8; ++i)
        fprintf(stderr, " %02x", f->data[i]);
    fprintf(stderr, "\n");
}

static void check_queue_fields(int64_t depth, int64_t free_)
{
    if (o.queue_capacity == 0)
        o.queue_capacity = (unsigned)(depth + free_);
    FUZZ_CHECK(o.queue_capacity > 0 && depth + free_ == o.queue_capacity);
}

static void check_status(const rig *r, const int64_t *v)
{
    fw_inspection in;
    fw_inspect(r->c, &in);
    const fw_inspection *c = &in;
    FUZZ_CHECK(v[0] == c->state && v[1] == c->fault);
    const int64_t flags = v[2];
    FUZZ_CHECK((flags & 0xE0) == 0);
    FUZZ_CHECK(((flags & 1) != 0) == c->homed);
    if (!o.estop_cut) { /* an interrupt inside the STATUS's own reads makes these a moment old */
        FUZZ_CHECK(((flags & 2) != 0) == r->f.enabled);
        if (!o.estop_read_unsure)
            FUZZ_CHECK(((flags & 4) != 0) == o.estop_read);
    }
    FUZZ_CHECK(((flags & 16) != 0) == o.passive_read);
    check_queue_fields(v[3], v[4]);
    FUZZ_CHECK(v[3] == c->traj_depth);
    /* The last commit taken: as the answers said, or the commit being fed, when its answer has
     * gone out before this STATUS and is not judged yet (board timing: a STATUS falls due while
     * the commit is validated). */
    const bool feeding_commit = r->in_feed && o.wf.kind == WIRE_COMMAND &&
                                (o.wf.msg == PM_MOVE_COMMIT || o.wf.msg == PM_TRAJ_COMMIT) && v[5] == o.wf.seq;
    if (o.any_commit && !feeding_commit)
        FUZZ_CHECK(v[5] == o.last_commit);
    if (o.status_seen)
        FUZZ_CHECK(v[6] == (uint16_t)(o.status_counter + 1u));
    o.status_seen = true;
    o.status_counter = (uint16_t)v[6];
}

/* SLIDES: the steps emitted as of the last control tick (what it published), in nanometres; once
 * homed they are the plant's true positions then. */
static void check_slides(const rig *r, int first, const int64_t *v)
{
    if (!fw_homed_of(r->c) || o.estop_cut)
        return;
    const double spm = (double)o.params.v[FP_STEPS_PER_M];
    for (int i = 0; i < 2; ++i) {
        if ((o.zero_suspect >> (first + i)) & 1u)
            continue;
        const double nm = (double)o.steps_read[first + i] * 1e9 / spm;
        const double nm_handed = (double)o.steps_handed[first + i] * 1e9 / spm;
        bool ok = fabs((double)v[i] - nm) <= 1.0 + 1e-6 * fabs(nm) ||
                  (o.handed && fabs((double)v[i] - nm_handed) <= 1.0 + 1e-6 * fabs(nm_handed));
        for (unsigned j = 0; j < o.n_ticks && j < 8u && !ok; ++j) {
            const double nm_tick = (double)o.steps_ticks[j][first + i] * 1e9 / spm;
            ok = fabs((double)v[i] - nm_tick) <= 1.0 + 1e-6 * fabs(nm_tick);
        }
        if (trace && !ok)
            fprintf(stderr, "slide %d: SLIDES %lld nm, plant %d steps (%.0f nm)\n", first + i,
                    (long long)v[i], (int)o.steps_read[first + i], nm);
        FUZZ_CHECK(ok);
    }
}

/* Everything the controller sent since the last look; periodic output is checked here, answers
 * are counted for the caller.  The transmit buffer is emptied. */
static void read_outputs(rig *r, oracle_outputs *out)
{
    memset(out, 0, sizeof *out);
    for (unsigned i = 0; i < r->f.tx_count; ++i) {
        const unsigned fn = r->f.tx[i].id >> 4;
        if (trace && (fn < 0x20 || fn > 0x26)) /* not STATUS, SLIDES, FK */
            trace_frame(r, "  <-", &r->f.tx[i]);
        int64_t v[PROTO_MAX_FIELDS];
        const proto_msg m = wire_read_sent(&r->f.tx[i], r->cfg.node, v);
        switch (m) {
        case PM_ACK:
            ++out->n_ack;
            out->ack_at = (int)i;
            memcpy(out->ack, v, sizeof v);
            check_queue_fields(v[2], v[3]);
            summary_answer((uint8_t)v[0], 0, FW_REASON_NONE);
            break;
        case PM_REJECT:
            ++out->n_rej;
            memcpy(out->rej, v, sizeof v);
            FUZZ_CHECK(v[2] > FW_REASON_NONE && v[2] < FW_REASON_COUNT);
            summary_answer((uint8_t)v[0], 1, (fw_reason)v[2]);
            break;
        case PM_PARAM_VALUE:
            ++out->n_pv;
            memcpy(out->pv, v, sizeof v);
            break;
        case PM_INFO:
            ++out->n_info;
            out->info_at = (int)i;
            memcpy(out->info, v, sizeof v);
            break;
        case PM_BOARD:
            ++out->n_board;
            out->board_at = (int)i;
            memcpy(out->board, v, sizeof v);
            break;
        case PM_STATUS:
            if (!FUZZ_BOARD_TIME) /* (else judged as it was sent: oracle_sent) */
                check_status(r, v);
            break;
        case PM_SLIDES_A:
        case PM_SLIDES_B:
        case PM_SLIDES_C:
            if (!FUZZ_BOARD_TIME) /* (else judged as they were sent: oracle_sent) */
                check_slides(r, 2 * (m - PM_SLIDES_A), v);
            fk_check_frame(&o, r, m, v);
            break;
        case PM_FK_A:
        case PM_FK_B:
        case PM_FK_C:
            fk_check_frame(&o, r, m, v);
            break;
        case PM_TRAJ_END: /* a fault travels with the fault ending, and only with it */
            FUZZ_CHECK((v[1] == FW_TRAJ_END_FAULT) == (v[2] != FW_FAULT_NONE));
            break;
        default:
            break;
        }
    }
    r->f.tx_count = 0;
    fk_check_burst(&o, r);
    o.n_ticks = 0;
}

/* What the controller promises whenever it is looked at. */
/* ran: a control tick has just run (not a poll, nor only an input changed). */
static void observe(rig *r, bool ran)
{
    fw_inspection in;
    fw_inspect(r->c, &in);
    const fw_inspection *c = &in;
    const fw_state s = c->state;
    FUZZ_CHECK((unsigned)s < FW_STATE_COUNT && s != FW_STATE_BOOT);
    /* An e-stop interrupt before this control tick began has been completed by it, first thing
     * (fw/runtime.h: the tick completes it; the thread's work leaves it to the tick, but for a
     * command it hands over, which the tick's side completes first, in place). */
    if (ran) {
        if (o.estop_cut && !o.cut_inside)
            FUZZ_CHECK(s == FW_STATE_ESTOP);
        o.cut_inside = false;
    }
    if (s != o.state) {
        if (trace)
            fprintf(stderr, "%9.3f ms state %s -> %s (fault %s, pending %s, overruns %u)\n",
                    (double)r->f.now_us / 1000.0, proto_enum_name(proto_state_names, o.state),
                    proto_enum_name(proto_state_names, s), proto_enum_name(proto_fault_names, c->fault),
                    proto_enum_name(proto_fault_names, c->pending_fault), (unsigned)c->sg_overruns);
        /* On the board's timing a command is taken by the tick that also supervises: a tick
         * inside a frame's poll may make the command's transition and one of its own. */
        unsigned allowed = next_states[o.state];
        if (FUZZ_BOARD_TIME && ran && r->in_feed)
            for (int x = 0; x < FW_STATE_COUNT; ++x)
                if (next_states[o.state] & BIT(x))
                    allowed |= next_states[x];
        FUZZ_CHECK(allowed & BIT(s));
        summary_state(o.state, s);
        if (s == FW_STATE_FAULT || s == FW_STATE_ESTOP)
            summary_fault(c->fault);
        if (s != FW_STATE_MOVING && s != FW_STATE_STOPPING)
            o.traj_running = o.traj_stopped = false;
        if (s == FW_STATE_HOMING) {
            o.zero_suspect = 0;
            suspect_zero(r);
        }
        o.state = s;
    }
    if (s == FW_STATE_ESTOP)
        o.estop_cut = false;
    /* A latched fault belongs to the fault state, the e-stop's to the e-stop state, none to the
     * others (CLEAR_FAULT clears it). */
    if (s == FW_STATE_FAULT)
        FUZZ_CHECK(c->fault != FW_FAULT_NONE && c->fault != FW_FAULT_ESTOP && c->fault < FW_FAULT_COUNT);
    else if (s == FW_STATE_ESTOP)
        FUZZ_CHECK(c->fault == FW_FAULT_ESTOP);
    else
        FUZZ_CHECK(c->fault == FW_FAULT_NONE);
    /* Drives: energised exactly in the states that may move the robot (ENABLE energises, DISABLE,
     * CLEAR_FAULT, faults and e-stops leave them off), and off from the e-stop interrupt on. */
    const bool active = s == FW_STATE_IDLE || s == FW_STATE_HOMING || s == FW_STATE_MOVING ||
                        s == FW_STATE_STOPPING;
    FUZZ_CHECK(r->f.enabled == (active && !o.estop_cut));
    if (!o.estop_cut)
        FUZZ_CHECK(c->drives_on == r->f.enabled);
    /* At rest no trajectory point waits (a STOP's promise, and a finished or dropped one's). */
    if (s != FW_STATE_MOVING && s != FW_STATE_STOPPING)
        FUZZ_CHECK(c->traj_depth == 0);
    /* The parameters are what the answers said, and the drivers are programmed with them (not
     * judged inside a frame's poll, before its answer: a PARAM_SET taken by a tick there). */
    if (!r->in_feed) {
        FUZZ_CHECK(memcmp(&c->params, &o.params, sizeof o.params) == 0);
        FUZZ_CHECK(r->f.pulse_ns == (uint32_t)o.params.v[FP_STEP_PULSE_NS]);
        FUZZ_CHECK(r->f.dir_setup_ns == (uint32_t)o.params.v[FP_DIR_SETUP_NS]);
    }
    /* The fake's step interrupt never runs late, so an overrun is the controller asking its step
     * generator for more than the generator can give (stepgen.h: the planner keeps every segment
     * within capacity): with any parameter set the controller accepted, none may happen. */
    FUZZ_CHECK(c->sg_overruns == 0);
    FUZZ_CHECK(c->fault != FW_FAULT_STEP_OVERRUN && c->pending_fault != FW_FAULT_STEP_OVERRUN);
    /* The watchdog: a watchdog fault only after silence past the timeout (docs/protocol.md),
     * judged when it is raised (pending while the robot is brought to rest, or latched at once). */
    const uint64_t now = r->f.now_us;
    const uint64_t wd_us = (uint64_t)o.params.v[FP_WATCHDOG_MS] * 1000u;
    if ((c->pending_fault == FW_FAULT_WATCHDOG && o.seen_pending != FW_FAULT_WATCHDOG) ||
        (c->fault == FW_FAULT_WATCHDOG && o.seen_fault != FW_FAULT_WATCHDOG &&
         o.seen_pending != FW_FAULT_WATCHDOG))
        FUZZ_CHECK(wd_us > 0 && now - o.last_alive_us >= wd_us);
    o.seen_fault = c->fault;
    o.seen_pending = c->pending_fault;
    if (c->homed && !o.homed)
        summary_homed();
    o.homed = c->homed;
    plant_check_stroke(r);
}

void oracle_start(rig *r, const fw_param_set *saved)
{
    if (trace < 0)
        trace = getenv("TSE_FUZZ_TRACE") ? atoi(getenv("TSE_FUZZ_TRACE")) : 0;
    if (trace)
        fprintf(stderr, "start: fixture %d\n", (int)r->fixture);
    memset(&o, 0, sizeof o);
    if (saved)
        o.saved = *saved;
    else
        fw_params_default(&o.saved);
    oracle_reboot(r);
}

void oracle_reboot(rig *r)
{
    const fw_param_set saved = o.saved;
    memset(&o, 0, sizeof o);
    /* A restart loads what PARAM_SAVE stored (the fixture's record before any). */
    o.saved = o.params = saved;
    o.state = FW_STATE_DISABLED;
    FUZZ_CHECK(fw_state_of(r->c) == FW_STATE_DISABLED);
    o.estop_read = o.passive_read = false; /* no control tick has read them yet */
    FUZZ_CHECK(!fw_homed_of(r->c));
    rig_plant_follow(r, &o.params);
    plant_check_reset(r, &o.params);
    plant_check_zero_suspect(0);
    observe(r, true);
}

void oracle_before_frame(rig *r, const hal_can_frame *f)
{
    if (trace && (f->id >> 4) != 0x05)
        trace_frame(r, "->", f);
    wire_classify(f, r->cfg.node, &o.wf);
    snapshot_take(r, &o.before);
    o.estop_open_before = r->f.estop_open;
    o.storage_fails_before = r->f.storage_fails;
    o.spent_now = false;
    o.cut_pending = o.estop_cut;
    o.fed_us = r->f.now_us;
}

/* The commands the thread hands over to the tick (fw/runtime.h), which publishes its view as it
 * takes one: in this rig in the middle of a segment. */
static bool hands_over(const wire_frame *w)
{
    if (w->kind != WIRE_COMMAND && !(w->kind == WIRE_BROADCAST && w->well_formed))
        return false;
    switch (w->msg) {
    case PM_ESTOP:
    case PM_STOP:
    case PM_ENABLE:
    case PM_DISABLE:
    case PM_CLEAR_FAULT:
    case PM_HOME:
    case PM_MOVE_COMMIT:
    case PM_TRAJ_COMMIT:
    case PM_PARAM_SET:
        return true;
    default:
        return false;
    }
}

void oracle_after_frame(rig *r)
{
    const wire_frame *w = &o.wf;
    if (hands_over(w)) {
        memcpy(o.steps_handed, r->f.steps, sizeof o.steps_handed);
        o.handed = true;
    }
    oracle_outputs out;
    read_outputs(r, &out);
    /* An e-stop interrupt inside the frame's poll, or one the poll completes before it handles
     * the frame: the state the frame was judged in is not the snapshot's. */
    const bool hooked = r->hook_fired_in_feed || o.cut_pending || r->ticks_in_feed;
    oracle_judge_answers(&o, r, &out, hooked);
    /* Nothing of a refused command is applied (a content refusal spends its number), and nothing
     * of INFO_GET, which only asks. */
    const bool asks = w->kind == WIRE_COMMAND && w->msg == PM_INFO_GET;
    if ((out.n_rej || asks) && !hooked) {
        snapshot after;
        snapshot_take(r, &after);
        const char *what = "";
        if (!snapshot_same(&o.before, &after, o.spent_now, r->steps_in_feed, &what)) {
            fprintf(stderr, "%s frame 0x%03x changed %s\n", asks ? "INFO_GET" : "refused", (unsigned)(w->function << 4),
                    what);
            FUZZ_CHECK(!"a refused frame, or INFO_GET, changed the controller");
        }
    }
    observe(r, false);
}

void oracle_after_poll(rig *r)
{
    oracle_outputs out;
    read_outputs(r, &out);
    /* No frame, no answer: an answer here would be a second one to an earlier frame. */
    FUZZ_CHECK(out.n_ack + out.n_rej + out.n_pv + out.n_info + out.n_board == 0);
    observe(r, false);
}

void oracle_event(rig *r)
{
    if (fw_state_of(r->c) == FW_STATE_HOMING)
        suspect_zero(r);
    oracle_outputs out;
    read_outputs(r, &out);
    FUZZ_CHECK(out.n_ack + out.n_rej + out.n_pv + out.n_info + out.n_board == 0);
    observe(r, false);
}

void oracle_published(rig *r)
{
    memcpy(o.steps_handed, r->f.steps, sizeof o.steps_handed);
    o.handed = true;
}

void oracle_after_control(rig *r)
{
    fw_inspection in;
    fw_inspect(r->c, &in);
    const fw_inspection *c = &in;
    /* The control tick supervises first: an e-stop input open before it began has put the
     * controller in ESTOP by now (docs/controller.md, "E-stop": it cuts stepping at once). */
    FUZZ_CHECK(!r->f.estop_open || o.cut_inside || c->state == FW_STATE_ESTOP);
    o.estop_read = r->f.estop_open;
    /* The interrupt opens the input: inside the tick, the tick's read of it may have come first,
     * and in estop nothing else says which (the cut is complete at once, the state unchanged). */
    o.estop_read_unsure = o.cut_inside;
    o.passive_read = r->f.can_state.error_passive;
    memcpy(o.steps_read, r->f.steps, sizeof o.steps_read);
    memcpy(o.steps_ticks[o.n_ticks++ % 8u], r->f.steps, sizeof o.steps_read);
    o.handed = false;
    observe(r, true);
    /* Silence past the watchdog timeout, one control period to notice: the robot is being
     * stopped or the fault latched (docs/protocol.md, HOST_HEARTBEAT). */
    const uint64_t wd_us = (uint64_t)o.params.v[FP_WATCHDOG_MS] * 1000u;
    /* (On the board's timing an ENABLE is taken by the tick up to a period after it was fed, and
     * inside a frame's poll the frame's answer is not judged yet.) */
    const uint64_t notice = (FUZZ_BOARD_TIME ? 2u : 1u) * 1000000u / r->cfg.segment_hz;
    if (c->drives_on && wd_us > 0 && !r->in_feed && r->f.now_us - o.last_alive_us > wd_us + notice)
        FUZZ_CHECK(c->pending_fault != FW_FAULT_NONE || c->state == FW_STATE_FAULT);
}

void oracle_segment(rig *r)
{
    if (trace > 1 && (fw_state_of(r->c) == FW_STATE_MOVING || fw_state_of(r->c) == FW_STATE_STOPPING)) {
        fw_inspection in;
        fw_inspect(r->c, &in);
        const fw_inspection *c = &in;
        fprintf(stderr, "%9.3f ms steps", (double)r->f.now_us / 1000.0);
        for (int k = 0; k < 6; ++k)
            fprintf(stderr, " %d", (int)r->f.steps[k]);
        fprintf(stderr, " q0 %.6f tau %.4f stop %d %.4f/%.4f src %d\n", (double)c->q[0], (double)c->tau,
                c->stopping, (double)c->stop_t, (double)c->stop_T, (int)c->src);
    }
    plant_check_segment(r);
}

void oracle_estop_isr(rig *r, bool inside)
{
    (void)r;
    o.estop_cut = true;
    o.cut_inside = inside;
}

void oracle_sent(rig *r, const hal_can_frame *f)
{
    int64_t v[PROTO_MAX_FIELDS];
    if (!FUZZ_BOARD_TIME)
        return;
    /* On the board's timing a validation looks at the bus between its pieces and sends what falls
     * due meanwhile (fw_telemetry_look), ticks later than the frame began: judged against the
     * state and the steps of the tick last run as it goes out. */
    const proto_msg m = wire_read_sent(f, r->cfg.node, v);
    if (m == PM_STATUS)
        check_status(r, v);
    else if (m >= PM_SLIDES_A && m <= PM_SLIDES_C)
        check_slides(r, 2 * (m - PM_SLIDES_A), v);
}

void oracle_pulse(rig *r, uint8_t mask)
{
    plant_check_pulse(r, mask, o.estop_cut);
}

void oracle_dir(rig *r, uint8_t forward_mask)
{
    plant_check_dir(r, forward_mask);
}
