#include "oracle_model.h"

#include <math.h>
#include <stdio.h>

#include "fuzz_target.h"
#include "plant_check.h"

/* docs/protocol.md, "Which command each state accepts": 'A' accepted, '-' refused with `state`.
 * Columns: boot, disabled, homing, idle, moving, stopping, fault, estop. */
static const char *const accepts[PM_COUNT] = {
    [PM_ESTOP] = "AAAAAAAA",        [PM_STOP] = "-AAAAAAA",        [PM_HOST_HEARTBEAT] = "AAAAAAAA",
    [PM_ENABLE] = "-A------",       [PM_DISABLE] = "-A-A--AA",     [PM_HOME] = "---A----",
    [PM_CLEAR_FAULT] = "------AA",  [PM_POSE_A] = "-AAAAAAA",      [PM_POSE_B] = "-AAAAAAA",
    [PM_POSE_C] = "-AAAAAAA",       [PM_MOVE_COMMIT] = "---AA---", [PM_TRAJ_COMMIT] = "---AA---",
    [PM_PARAM_GET] = "AAAAAAAA",    [PM_PARAM_SET] = "-A----AA",   [PM_PARAM_SAVE] = "-A----AA",
    [PM_INFO_GET] = "AAAAAAAA",
    /* The bootloader's: BOOT_ENTER only with the drives off, the others never (an application). */
    [PM_BOOT_ENTER] = "AA----AA",   [PM_BOOT_QUERY] = "--------",  [PM_BOOT_ERASE] = "--------",
    [PM_BOOT_WRITE] = "--------",   [PM_BOOT_VERIFY] = "--------", [PM_BOOT_START] = "--------",
    [PM_BOOT_DATA] = "--------",
};

/* PARAM_SET: what clears homed when it changes (docs/protocol.md); the margins and limits keep it. */
static bool rezeroes(unsigned id)
{
    return id == FP_STEPS_PER_M || (id >= FP_HOME_SW_1 && id <= FP_HOME_SW_6) ||
           id <= FP_S_MAX; /* L, k1, eta, k3, k4, alpha_min, alpha_max, s_min, s_max: ids 0..8 */
}

/* Sequence numbers: newer is ahead by 1..127 modulo 256. */
static bool newer(uint8_t seq, uint8_t than)
{
    const uint8_t d = (uint8_t)(seq - than);
    return d != 0 && d < 128u;
}

/* A REJECT's fields other than function, seq and reason, by reason (docs/protocol.md). */
static void check_reject_details(const int64_t *v, fw_state state_before, bool state_known)
{
    const int64_t reason = v[2], scissor = v[3], kin = v[4], field = v[5], where = v[6];
    switch (reason) {
    case FW_REASON_KINEMATICS:
        FUZZ_CHECK(scissor >= 1 && scissor <= 3 && kin >= 1 && kin <= 8 && where <= 1000);
        break;
    case FW_REASON_TIMING: {
        /* The slide, plus 16 times the limit (fw_slide_limit). */
        const int64_t slide = field % 16, limit = field / 16;
        FUZZ_CHECK(slide >= 1 && slide <= 6 && scissor == (slide + 1) / 2 && kin == 0 && limit < FW_LIMIT_COUNT);
        break;
    }
    case FW_REASON_PARAM_SET: /* the rule the set breaks, always said */
        FUZZ_CHECK(scissor == 0 && kin == 0 && where > FW_RULE_NONE && where < FW_RULE_COUNT);
        break;
    case FW_REASON_STATE:
        FUZZ_CHECK(scissor == 0 && kin == 0 && where == 0);
        if (state_known)
            FUZZ_CHECK(field == state_before);
        break;
    case FW_REASON_ENDED: /* how (a traj_end) + 16 x the fault; where: ms since it ended */
        FUZZ_CHECK(scissor == 0 && kin == 0 && (field & 15) < FW_TRAJ_END_COUNT && (field >> 4) < FW_FAULT_COUNT);
        FUZZ_CHECK(((field >> 4) != 0) == ((field & 15) == FW_TRAJ_END_FAULT) && where >= 0 && where <= 65535);
        break;
    case FW_REASON_TOO_LONG: /* 0: longer than a move may last (where, s); 1: unproven near a limit */
        if (field == 0)
            FUZZ_CHECK(scissor == 0 && kin == 0 && where == FW_MOVE_MAX_S);
        else
            FUZZ_CHECK(field == 1 && scissor >= 1 && scissor <= 3 && kin != 0 && where >= 0 && where <= 1000);
        break;
    case FW_REASON_ORDER: /* field: the sequence number expected */
        FUZZ_CHECK(scissor == 0 && kin == 0 && where == 0);
        break;
    default:
        FUZZ_CHECK(scissor == 0 && kin == 0 && where == 0);
        break;
    }
}

static bool staged_complete(const oracle_model *o, uint8_t seq)
{
    return o->stage_have == 7u && o->stage_seq == seq;
}

static void check_target(const oracle_model *o, const tse_real *to)
{
    for (int k = 0; k < 6; ++k)
        FUZZ_CHECK(fabs(to[k] - (tse_real)o->stage_v[k] * TSE_R(1e-6)) <= TSE_R(1e-9));
}

/* A trajectory row's place (docs/protocol.md, "Streaming a trajectory"), from the controller's
 * trajectory bookkeeping before the frame: a row other than a first joins the open trajectory of
 * its identity with the next sequence number, or is refused `order`; a row of the trajectory that
 * ended last is refused `ended` (in any state: `ended_only` asks only for that), and so is one of
 * no trajectory running.  The refusal's field in *field. */
static fw_reason row_place(const oracle_model *o, bool ended_only, int64_t *field)
{
    const fw_inspection *b = &o->before.in;
    const uint8_t id = (uint8_t)o->wf.v[3];
    *field = 0;
    if (o->wf.v[2] & PROTO_TRAJ_FIRST)
        return FW_REASON_NONE;
    if (b->run_open && id == b->run_id) {
        if (ended_only || o->wf.seq == b->run_next_seq)
            return FW_REASON_NONE;
        *field = b->run_next_seq;
        return FW_REASON_ORDER;
    }
    if (b->run_ended != FW_TRAJ_END_NONE && id == b->run_ended_id) {
        *field = b->run_ended + 16 * (int64_t)b->run_fault;
        return FW_REASON_ENDED;
    }
    return ended_only ? FW_REASON_NONE : FW_REASON_ENDED;
}

/* A commit's answer against the staging rules: applied only when all three parts of its number
 * arrived and the number is newer than the last commit; refused for its content, it spends the
 * number (docs/protocol.md). */
static void judge_commit(oracle_model *o, const rig *r, const oracle_outputs *out, uint8_t seq)
{
    const bool complete = staged_complete(o, seq);
    const bool fresh = !o->any_commit || newer(seq, o->last_commit);
    const bool traj = o->wf.msg == PM_TRAJ_COMMIT, first = traj && (o->wf.v[2] & PROTO_TRAJ_FIRST);
    int64_t field = 0;
    const fw_reason place = traj ? row_place(o, false, &field) : FW_REASON_NONE;
    /* Its place among the trajectories is judged before its pose. */
    if (place != FW_REASON_NONE) {
        FUZZ_CHECK(out->n_rej && out->rej[2] == place && out->rej[5] == field);
        return;
    }
    bool spends = false;
    if (out->n_ack) {
        FUZZ_CHECK(complete && fresh && o->before.in.homed);
        spends = true;
        fw_inspection in;
        fw_inspect(r->c, &in);
        const fw_inspection *c = &in;
        if (o->wf.msg == PM_MOVE_COMMIT) {
            check_target(o, o->before.in.state == FW_STATE_MOVING ? c->next.to : c->move.to);
            /* The planned duration is at least the one asked for. */
            if (o->wf.v[1] == 0)
                FUZZ_CHECK(out->ack[4] + 1 >= o->wf.v[2]);
        } else {
            check_target(o, c->traj_tail);
            /* A trajectory starts with its first row, at rest; the others join it while it runs. */
            FUZZ_CHECK(first == (o->before.in.state == FW_STATE_IDLE));
            if (first)
                o->traj_running = true;
        }
        /* (On the board's timing the tick that took it may also have begun a stop: a fault
         * raised in the same tick, an e-stop.) */
        if (o->before.in.state == FW_STATE_IDLE)
            FUZZ_CHECK(c->state == FW_STATE_MOVING ||
                       (r->ticks_in_feed && (c->state == FW_STATE_STOPPING || c->state == FW_STATE_FAULT ||
                                             c->state == FW_STATE_ESTOP || c->state == FW_STATE_IDLE)));
    } else {
        switch (out->rej[2]) {
        case FW_REASON_INCOMPLETE:
            FUZZ_CHECK(!complete);
            break;
        case FW_REASON_STALE:
            FUZZ_CHECK(!fresh);
            break;
        case FW_REASON_NOT_HOMED:
            FUZZ_CHECK(!o->before.in.homed);
            break;
        case FW_REASON_KINEMATICS:
        case FW_REASON_TIMING:
        case FW_REASON_RANGE:
        case FW_REASON_TOO_LONG:
            /* Refused for its content: the content was there to refuse. */
            FUZZ_CHECK(complete && fresh && o->before.in.homed);
            spends = true;
            break;
        case FW_REASON_QUEUE_FULL:
            break;
        case FW_REASON_STATE: /* the state table accepts it, but not in every kind of motion */
            FUZZ_CHECK(o->before.in.state == FW_STATE_MOVING);
            break;
        case FW_REASON_ORDER:
        case FW_REASON_ENDED:
            FUZZ_CHECK(!"a row refused for its place, which row_place gives none");
            break;
        default:
            FUZZ_CHECK(!"a commit refused for a reason that cannot be its");
        }
    }
    if (o->wf.msg == PM_TRAJ_COMMIT && o->traj_stopped)
        FUZZ_CHECK(out->n_rej == 1); /* no point of a stopped trajectory is taken */
    if (spends) {
        o->spent_now = out->n_rej != 0;
        o->any_commit = true;
        o->last_commit = seq;
        o->stage_have = 0;
    }
}

static void judge_pose(oracle_model *o, const oracle_outputs *out)
{
    const uint8_t seq = (uint8_t)o->wf.v[0];
    /* Refused only when not newer than the last commit; a part of another number than the staged
     * one starts the staging afresh (docs/protocol.md). */
    const bool spent = o->any_commit && !newer(seq, o->last_commit);
    FUZZ_CHECK(out->n_ack == 0 && out->n_pv == 0 && out->n_rej <= 1);
    FUZZ_CHECK(out->n_rej == (spent ? 1 : 0));
    if (out->n_rej) {
        FUZZ_CHECK(out->rej[2] == FW_REASON_STALE);
        return;
    }
    if (o->stage_have != 0 && seq != o->stage_seq)
        o->stage_have = 0;
    const int part = o->wf.msg - PM_POSE_A;
    o->stage_seq = seq;
    o->stage_have |= (uint8_t)(1u << part);
    o->stage_v[2 * part] = (int32_t)o->wf.v[1];
    o->stage_v[2 * part + 1] = (int32_t)o->wf.v[2];
}

static void judge_params(oracle_model *o, rig *r, const oracle_outputs *out, bool hooked)
{
    const wire_frame *w = &o->wf;
    const int64_t id = w->v[0];
    const int64_t named = id > 255 ? 255 : id;
    if (w->msg == PM_PARAM_SAVE) {
        FUZZ_CHECK(out->n_pv == 0);
        if (o->storage_fails_before) {
            FUZZ_CHECK(out->n_rej && out->rej[2] == FW_REASON_STORAGE);
        } else {
            FUZZ_CHECK(out->n_ack);
            o->saved = o->params;
        }
        return;
    }
    if (id >= FP_COUNT) {
        FUZZ_CHECK(out->n_rej && out->rej[2] == FW_REASON_PARAM_UNKNOWN && out->rej[5] == named);
        FUZZ_CHECK(out->n_pv == 0);
        return;
    }
    if (w->msg == PM_PARAM_GET) {
        FUZZ_CHECK(out->n_ack && out->n_pv == 1 && out->pv[0] == id && out->pv[1] == o->params.v[id]);
        return;
    }
    const int64_t value = w->v[1];
    const fw_param_def *d = &fw_param_table[id];
    if (value < d->min || value > d->max) {
        FUZZ_CHECK(out->n_rej && out->rej[2] == FW_REASON_PARAM_RANGE && out->rej[5] == named);
        FUZZ_CHECK(out->n_pv == 0);
        return;
    }
    if (out->n_rej) {
        FUZZ_CHECK(out->rej[2] == FW_REASON_PARAM_SET || out->rej[2] == FW_REASON_PARAM_RANGE);
        FUZZ_CHECK(out->rej[5] == named && out->n_pv == 0);
        return;
    }
    FUZZ_CHECK(out->n_pv == 1 && out->pv[0] == id && out->pv[1] == value);
    const bool changed = o->params.v[id] != value;
    o->params.v[id] = (int32_t)value;
    if (rezeroes((unsigned)id) && changed)
        FUZZ_CHECK(!fw_homed_of(r->c));
    else if (!hooked) /* (an e-stop drops the zero) */
        FUZZ_CHECK(fw_homed_of(r->c) == o->before.in.homed);
    rig_plant_follow(r, &o->params);
    plant_check_reset(r, &o->params);
}

/* INFO_GET (pages 0 and 1, the ones the table takes): its ACK, then at once, for page 0, INFO with
 * the project's version (TSE_EXPECT_VERSION, as CMake has it) and the rates the rig configured
 * the controller with; for page 1, BOARD with the rig's board name (RIG_BOARD_NAME), a character
 * a byte, NUL after it.  That it changed nothing is judged with the refusals' snapshot
 * (oracle.c). */
static void judge_info(const rig *r, const oracle_outputs *out, int64_t page)
{
    static int version[3] = {-1, -1, -1};
    if (version[0] < 0)
        FUZZ_CHECK(sscanf(TSE_EXPECT_VERSION, "%d.%d.%d", &version[0], &version[1], &version[2]) == 3);
    if (page == 1) {
        static const char name[8] = RIG_BOARD_NAME; /* shorter than 8: NUL-padded */
        FUZZ_CHECK(out->n_ack == 1 && out->n_board == 1 && out->n_info == 0 && out->board_at == out->ack_at + 1);
        for (int k = 0; k < 8; ++k)
            FUZZ_CHECK(out->board[k] == (unsigned char)name[k]);
        return;
    }
    FUZZ_CHECK(out->n_ack == 1 && out->n_info == 1 && out->n_board == 0 && out->info_at == out->ack_at + 1);
    FUZZ_CHECK(out->info[0] == version[0] && out->info[1] == version[1] && out->info[2] == version[2]);
    FUZZ_CHECK(out->info[3] == r->cfg.step_hz && out->info[4] == r->cfg.segment_hz);
}

/* The effect an accepted command must have had (strict: no e-stop interrupt in between), and
 * what it tells the model. */
static void judge_effect(oracle_model *o, rig *r, proto_msg m, bool strict)
{
    fw_inspection in;
    fw_inspect(r->c, &in);
    const fw_inspection *c = &in;
    const fw_state was = o->before.in.state, s = c->state;
    if (m == PM_ENABLE)
        o->last_alive_us = o->fed_us;
    if (m == PM_STOP)
        o->traj_stopped = o->traj_running;
    if (!strict)
        return;
    switch (m) {
    case PM_ESTOP:
        FUZZ_CHECK(s == FW_STATE_ESTOP && c->fault == FW_FAULT_ESTOP);
        break;
    case PM_STOP:
        if (was == FW_STATE_HOMING)
            FUZZ_CHECK(s == FW_STATE_STOPPING);
        else if (was == FW_STATE_MOVING) /* a motion whose last setpoints are stepping out ends as it is */
            FUZZ_CHECK(s == FW_STATE_STOPPING || s == FW_STATE_MOVING);
        else
            FUZZ_CHECK(s == was);
        break;
    case PM_ENABLE:
        FUZZ_CHECK(s == FW_STATE_IDLE);
        break;
    case PM_DISABLE:
        FUZZ_CHECK(s == (was == FW_STATE_IDLE ? FW_STATE_DISABLED : was));
        break;
    case PM_HOME:
        FUZZ_CHECK(s == FW_STATE_HOMING && !c->homed);
        break;
    case PM_CLEAR_FAULT:
        FUZZ_CHECK(s == FW_STATE_DISABLED && c->fault == FW_FAULT_NONE);
        break;
    default:
        break;
    }
}

static void judge_command(oracle_model *o, rig *r, const oracle_outputs *out, bool hooked)
{
    const wire_frame *w = &o->wf;
    const proto_msg m = w->msg;
    const fw_state was = o->before.in.state;
    if (m == PM_HOST_HEARTBEAT) {
        FUZZ_CHECK(out->n_ack + out->n_rej + out->n_pv == 0);
        o->last_alive_us = o->fed_us;
        return;
    }
    if (m == PM_POSE_A || m == PM_POSE_B || m == PM_POSE_C) {
        judge_pose(o, out); /* staging is the same in every state after boot */
        return;
    }
    /* Every other command: exactly one answer, with its function and sequence number. */
    FUZZ_CHECK(out->n_ack + out->n_rej == 1);
    const int64_t *a = out->n_ack ? out->ack : out->rej;
    FUZZ_CHECK(a[0] == w->function && a[1] == (w->has_seq ? w->seq : 0));
    if (out->n_rej)
        check_reject_details(out->rej, was, !hooked);
    if (m != PM_PARAM_GET && m != PM_PARAM_SET)
        FUZZ_CHECK(out->n_pv == 0);
    if (m != PM_INFO_GET)
        FUZZ_CHECK(out->n_info == 0 && out->n_board == 0);
    /* A row of the trajectory that ended last is refused as such whatever the state. */
    if (m == PM_TRAJ_COMMIT) {
        int64_t field = 0;
        const fw_reason ended = row_place(o, true, &field);
        if (ended != FW_REASON_NONE && !hooked) {
            FUZZ_CHECK(out->n_rej && out->rej[2] == ended && out->rej[5] == field);
            return;
        }
        if (hooked && out->n_rej && out->rej[2] == FW_REASON_ENDED)
            return; /* the interrupt's e-stop may have ended the trajectory first */
    }
    /* With an e-stop interrupt in the poll, the state the frame met is the snapshot's or ESTOP:
     * what depends on it is not judged, but what was answered still updates the model. */
    if (!hooked && accepts[m][was] == '-') {
        FUZZ_CHECK(out->n_rej && out->rej[2] == FW_REASON_STATE);
        return;
    }
    if (hooked && out->n_rej && out->rej[2] == FW_REASON_STATE)
        return;
    switch (m) {
    case PM_ESTOP:
    case PM_STOP:
    case PM_ENABLE:
    case PM_DISABLE:
    case PM_HOME:
        FUZZ_CHECK(hooked || out->n_ack);
        break;
    case PM_CLEAR_FAULT: /* the e-stop input must be closed */
        if (!hooked)
            FUZZ_CHECK(out->n_ack ? !o->estop_open_before
                                  : out->rej[2] == FW_REASON_STATE && o->estop_open_before);
        break;
    case PM_MOVE_COMMIT:
    case PM_TRAJ_COMMIT:
        judge_commit(o, r, out, w->seq);
        break;
    case PM_PARAM_GET:
    case PM_PARAM_SET:
    case PM_PARAM_SAVE:
        judge_params(o, r, out, hooked);
        break;
    case PM_INFO_GET:
        judge_info(r, out, w->v[0]);
        break;
    case PM_BOOT_ENTER: /* taken with the drives off: the controller now awaits its restart */
        FUZZ_CHECK(hooked || out->n_ack);
        if (out->n_ack)
            FUZZ_CHECK(fw_boot_requested(r->c) && !fw_drives_of(r->c));
        break;
    default:
        FUZZ_CHECK(!"a command without a rule");
    }
    if (out->n_ack)
        judge_effect(o, r, m, !hooked);
}

void oracle_judge_answers(oracle_model *o, rig *r, const oracle_outputs *out, bool hooked)
{
    const wire_frame *w = &o->wf;
    switch (w->kind) {
    case WIRE_OTHER_NODE:
    case WIRE_OWN_TRAFFIC:
    case WIRE_BROADCAST:
        /* Not ours, or a broadcast: nothing answers (only ESTOP and STOP are honoured). */
        FUZZ_CHECK(out->n_ack + out->n_rej + out->n_pv + out->n_info + out->n_board == 0);
        if (w->kind == WIRE_BROADCAST && w->well_formed && !hooked &&
            (w->msg == PM_ESTOP || (w->msg == PM_STOP && o->before.in.state != FW_STATE_BOOT)))
            judge_effect(o, r, w->msg, true);
        break;
    case WIRE_UNKNOWN:
    case WIRE_BAD_LENGTH:
    case WIRE_RANGE: {
        /* Malformed: one REJECT naming why, with the sequence number when the frame carries one
         * (a bad field other than it does not make it another's), 0 when it has none. */
        FUZZ_CHECK(out->n_rej == 1 && out->n_ack == 0 && out->n_pv == 0 && out->n_info == 0 && out->n_board == 0);
        const int64_t *v = out->rej;
        FUZZ_CHECK(v[0] == w->function && v[1] == (w->kind == WIRE_RANGE ? w->seq : 0));
        const fw_reason want = w->kind == WIRE_UNKNOWN      ? FW_REASON_UNKNOWN
                               : w->kind == WIRE_BAD_LENGTH ? FW_REASON_BAD_LENGTH
                                                            : FW_REASON_RANGE;
        FUZZ_CHECK(v[2] == want);
        if (want == FW_REASON_RANGE)
            FUZZ_CHECK(v[5] < PROTO_MAX_FIELDS && ((w->bad_fields >> v[5]) & 1u));
        break;
    }
    case WIRE_COMMAND:
        judge_command(o, r, out, hooked);
        break;
    }
}
