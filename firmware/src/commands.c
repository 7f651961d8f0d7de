#include "commands.h"

#include "adopt.h"
#include "fw/command_table.h"
#include "handover.h"
#include "inbox.h"
#include "planner.h"
#include "send.h"
#include "state.h"
#include "traj_rows.h"
#include "tse_version.h"

/* Sequence numbers wrap at 256: newer means ahead by 1..127. */
static bool newer(uint8_t seq, uint8_t than)
{
    const uint8_t d = (uint8_t)(seq - than);
    return d != 0 && d < 128u;
}

static void stage(fw_controller *c, const proto_message *m, uint8_t function)
{
    fw_thread *th = &c->th;
    const uint8_t seq = (uint8_t)m->v[0];
    /* Both refusals before anything changes: a refused part leaves the staged pose as it was. */
    if (th->any_commit && !newer(seq, th->last_seq)) {
        fw_reject(c, function, seq, FW_REASON_STALE, 0, NULL);
        return;
    }
    /* A part of another number starts the staging afresh, whichever of the two numbers is ahead:
     * parts of two numbers never mix, because a commit needs all three under its own number, and
     * a stray part staged under a number ahead of the host's (a second tool, a corrupted frame)
     * must not refuse the host's parts until a restart, as it would if it could not be displaced. */
    if (th->stage_have != 0 && seq != th->stage_seq)
        th->stage_have = 0;
    const int part = (int)m->msg - PM_POSE_A;
    th->stage_seq = seq;
    th->stage_have |= (uint8_t)(1u << part);
    th->stage_v[2 * part] = m->v[1];
    th->stage_v[2 * part + 1] = m->v[2];
}

/* The staged pose a commit of seq would move to, in SI units, or why there is none. */
static fw_reason commit_target(const fw_controller *c, uint8_t seq, tse_real pose[6])
{
    const fw_thread *th = &c->th;
    if (th->any_commit && !newer(seq, th->last_seq))
        return FW_REASON_STALE;
    if (th->stage_have != 7u || th->stage_seq != seq)
        return FW_REASON_INCOMPLETE;
    if (!(th->view.flags & FW_VIEW_HOMED))
        return FW_REASON_NOT_HOMED;
    for (int k = 0; k < 6; ++k)
        pose[k] = (tse_real)th->stage_v[k] * (TSE_R(1.0) / (tse_real)proto_pose_units(k));
    return FW_REASON_NONE;
}

static void accept_commit(fw_controller *c, uint8_t seq)
{
    c->th.last_seq = seq;
    c->th.any_commit = true;
    c->th.stage_have = 0;
}

/* A STOP or an ESTOP ended a validation (inbox.h): it is answered and handed over before the
 * commit it ended, which is then refused in the state it left. */
/* A frame as the controller takes it: its message, and how it answers. */
typedef struct {
    proto_message m;
    uint8_t function, seq;
    bool broadcast; /* nothing answers a broadcast */
} taken;

static bool admit(fw_controller *c, const hal_can_frame *f, taken *t);
static void state_command(fw_controller *c, const taken *t);

static void stop_first(fw_controller *c)
{
    hal_can_frame f;
    taken t;
    if (fw_inbox_take_stop(c, &f) && admit(c, &f, &t))
        state_command(c, &t); /* a STOP or an ESTOP (fw_inbox_take_stop takes no other) */
}

static void move_commit(fw_controller *c, const proto_message *m, uint8_t function)
{
    const uint8_t seq = (uint8_t)m->v[0];
    tse_real to[6];
    const fw_reason r = commit_target(c, seq, to);
    if (r != FW_REASON_NONE) {
        fw_reject(c, function, seq, r, 0, NULL);
        return;
    }
    const fw_view *v = &c->th.view;
    const bool queued = v->state == FW_STATE_MOVING;
    if (queued && (v->src != FW_SRC_MOVE || (v->flags & FW_VIEW_STOPPING))) {
        fw_reject(c, function, seq, FW_REASON_STATE, 0, NULL);
        return;
    }
    if (queued && (v->flags & FW_VIEW_HAS_NEXT)) {
        fw_reject(c, function, seq, FW_REASON_QUEUE_FULL, 0, NULL);
        return;
    }
    const fw_move_kind kind = m->v[1] == 0 ? FW_MOVE_DURATION : FW_MOVE_SPEED;
    const tse_real value =
        (tse_real)m->v[2] * (TSE_R(1.0) / (tse_real)(kind == FW_MOVE_DURATION ? PROTO_MS_PER_S : PROTO_UM_PER_M));
    fw_plan_result why;
    switch (fw_plan_commit(c, to, kind, value, queued, &why)) {
    case FW_PLAN_STOPPED:
        stop_first(c);
        fw_reject(c, function, seq, FW_REASON_STATE, 0, NULL);
        return;
    case FW_PLAN_REFUSED:
        fw_reject(c, function, seq, why.reason, 0, &why);
        /* A refused pose is spent: its sequence number cannot be committed again. */
        accept_commit(c, seq);
        return;
    case FW_PLAN_OK:
        break;
    }
    const fw_verdict verdict = fw_handover(c);
    if (verdict.reason != FW_REASON_NONE) {
        /* The state changed while it was planned (a fault, a stop, the running move's end short
         * of where this one starts): refused for the state, the number not spent. */
        fw_reject(c, function, seq, verdict.reason, 0, NULL);
        return;
    }
    accept_commit(c, seq);
    const fw_move *mv = &c->sh.req.u.move.mv;
    c->th.last_move = *mv;
    fw_ack(c, function, seq, (uint32_t)(mv->prof.T * TSE_R(1000.0) + TSE_R(0.5)));
    /* Per mille of the limit, rounded up: a demand over the limit never reads as at it. */
    const tse_real demand = mv->bound_ratio * TSE_R(1000.0);
    const int32_t info[5] = {seq, verdict.start, mv->bound, mv->bound_slide,
                             demand >= TSE_R(65535.0) ? 65535 : (int32_t)tse_ceil(demand)};
    fw_send(c, PM_MOVE_INFO, info);
}

static void traj_commit(fw_controller *c, const proto_message *m, uint8_t function)
{
    fw_thread *th = &c->th;
    const uint8_t seq = (uint8_t)m->v[0];
    const bool first = (m->v[2] & PROTO_TRAJ_FIRST) != 0, last = (m->v[2] & PROTO_TRAJ_LAST) != 0;
    uint8_t field;
    int32_t where;
    fw_reason r = fw_rows_refusal(c, m, false, &field, &where);
    if (r != FW_REASON_NONE) {
        fw_reject_row(c, function, seq, r, field, where);
        return;
    }
    tse_real to[6];
    r = commit_target(c, seq, to);
    /* A trajectory starts only at rest; while one runs, its rows join it. */
    if (r == FW_REASON_NONE && first && th->view.state != FW_STATE_IDLE)
        r = FW_REASON_STATE;
    /* A trajectory that takes no more points (after its last), or a full queue, changes nothing. */
    if (r == FW_REASON_NONE && !first && th->traj.closed)
        r = FW_REASON_STATE;
    if (r == FW_REASON_NONE && !first && th->view.traj_depth >= FW_TRAJ_CAPACITY)
        r = FW_REASON_QUEUE_FULL;
    if (r != FW_REASON_NONE) {
        fw_reject(c, function, seq, r, 0, NULL);
        return;
    }
    if (first)
        fw_traj_check_start(&th->traj, &th->lim, th->view.pose, th->view.q);
    fw_request *req = fw_handover_request(c, PM_TRAJ_COMMIT);
    req->u.row.first = first;
    req->u.row.id = (uint8_t)m->v[3];
    fw_traj_check *after = &th->traj_after;
    fw_plan_result why;
    fw_inbox_watch_begin(c, !first);
    const int rc = fw_traj_check_point(&th->traj, &th->geom, &th->lim, to, (uint32_t)m->v[1], last, &req->u.row.p,
                                       after, &why);
    if (fw_inbox_watch_end(c)) {
        /* A STOP (or an ESTOP) ended the row's validation: answered first, then the row is refused
         * as a row of the trajectory it ended, where it did (how, for the host: tse.can's Ended),
         * else for the state. */
        stop_first(c);
        fw_rows_collect(c);
        r = fw_rows_refusal(c, m, false, &field, &where);
        if (r == FW_REASON_ENDED)
            fw_reject_row(c, function, seq, r, field, where);
        else
            fw_reject(c, function, seq, FW_REASON_STATE, 0, NULL);
        return;
    }
    if (rc != 0) {
        fw_reject(c, function, seq, why.reason, 0, &why);
        /* Refused for its content (the pose, its timing), the number is spent, as for moves. */
        if (why.reason != FW_REASON_STATE)
            accept_commit(c, seq);
        return;
    }
    const fw_verdict verdict = fw_handover(c);
    if (verdict.reason == FW_REASON_ENDED) {
        /* The trajectory ended while the row was validated: refused as a row of it. */
        fw_rows_collect(c);
        r = fw_rows_refusal(c, m, false, &field, &where);
        fw_reject_row(c, function, seq, r != FW_REASON_NONE ? r : FW_REASON_ENDED, field, where);
        return;
    }
    if (verdict.reason != FW_REASON_NONE) {
        fw_reject(c, function, seq, verdict.reason, 0, NULL);
        return;
    }
    th->traj = *after;
    accept_commit(c, seq);
    fw_rows_took(c, seq, first, (uint8_t)m->v[3]);
    fw_ack(c, function, seq, 0);
}

static void param_value(fw_controller *c, uint16_t id)
{
    const int32_t v[2] = {id, c->th.params.v[id]};
    fw_send(c, PM_PARAM_VALUE, v);
}

/* INFO: the firmware's version (tse_version.h, from the project's) and the rates this controller
 * was configured with (fw_config), which the host tools judge its paths and sets at. */
_Static_assert(TSE_VERSION_MAJOR <= 255, "INFO carries the major version in a byte");
_Static_assert(TSE_VERSION_MINOR <= 255, "INFO carries the minor version in a byte");
_Static_assert(TSE_VERSION_PATCH <= 255, "INFO carries the patch version in a byte");

static void info(fw_controller *c)
{
    const int32_t v[5] = {TSE_VERSION_MAJOR, TSE_VERSION_MINOR, TSE_VERSION_PATCH, (int32_t)c->cfg.step_hz,
                          (int32_t)c->cfg.segment_hz};
    fw_send(c, PM_INFO, v);
}

/* BOARD: the platform's name for its board (fw_config.board), NUL-padded; a character the wire
 * cannot carry (not 7-bit ASCII) ends the name there, so that BOARD always goes out. */
static void board(fw_controller *c)
{
    int32_t v[PROTO_MAX_FIELDS] = {0};
    const char *name = c->cfg.board ? c->cfg.board : "";
    for (int i = 0; i < proto_wire[PM_BOARD].nfields && name[i] && (unsigned char)name[i] < 0x80u; ++i)
        v[i] = (unsigned char)name[i];
    fw_send(c, PM_BOARD, v);
}

static void param_set(fw_controller *c, const proto_message *m, uint8_t function)
{
    fw_thread *th = &c->th;
    const uint16_t id = (uint16_t)m->v[0];
    fw_param_set next = th->params;
    fw_param_fault why;
    const int r = fw_params_set_one(&next, id, m->v[1], &why);
    if (r != 0) {
        fw_reject_param(c, function, (fw_reason)r, id, r == FW_REASON_PARAM_SET ? why.rule : FW_RULE_NONE);
        return;
    }
    fw_request *req = fw_handover_request(c, PM_PARAM_SET);
    const fw_param_rule rule = fw_params_prepare(c, &next, &req->u.params);
    if (rule != FW_RULE_NONE) {
        fw_reject_param(c, function, FW_REASON_PARAM_SET, id, rule);
        return;
    }
    const fw_verdict verdict = fw_handover(c);
    if (verdict.reason == FW_REASON_PARAM_SET) {
        fw_reject_param(c, function, FW_REASON_PARAM_SET, id, verdict.rule);
        return;
    }
    if (verdict.reason != FW_REASON_NONE) {
        fw_reject(c, function, 0, verdict.reason, 0, NULL);
        return;
    }
    th->params = req->u.params.s;
    th->geom = req->u.params.g;
    th->lim = req->u.params.lim;
    fw_ack(c, function, 0, 0);
    param_value(c, id);
}

static void param_save(fw_controller *c, uint8_t function)
{
    uint8_t buf[256];
    const size_t n = fw_params_serialize(&c->th.params, buf, sizeof buf);
    if (n == 0 || c->hal.storage.save(c->hal.storage.ctx, buf, n) != 0) {
        fw_reject(c, function, 0, FW_REASON_STORAGE, 0, NULL);
        return;
    }
    fw_ack(c, function, 0, 0);
}

/* Whether message m's first field is a sequence number (a command's, echoed in its answer). */
static bool first_is_seq(proto_msg m)
{
    return proto_wire[m].nfields > 0 && proto_wire[m].fields[0].seq;
}

/* The sequence number of a frame refused by the codec: a field out of range leaves its sequence
 * number the frame's (a u8, never itself out of range), and the host matches the REJECT by it; a
 * frame of another length or an unknown function has none. */
static uint8_t range_seq(const hal_can_frame *f, uint8_t function, proto_error e)
{
    const proto_msg m = proto_find(function, PROTO_TO_CONTROLLER);
    if (e.reason != FW_REASON_RANGE || m == PM_COUNT || !first_is_seq(m))
        return 0;
    return f->data[proto_wire[m].fields[0].offset];
}


/* Whether frame f is a command of ours that the state allows, decoded into *t; a frame that is
 * not ours is dropped, one that is refused is answered. */
static bool admit(fw_controller *c, const hal_can_frame *f, taken *t)
{
    const uint8_t node = (uint8_t)(f->id & PROTO_NODE_MASK);
    t->function = (uint8_t)(f->id >> PROTO_NODE_BITS);
    t->broadcast = node == PROTO_BROADCAST;
    /* Frames for other controllers, and our own kind of traffic from other nodes, are not ours. */
    if (!t->broadcast && node != c->cfg.node)
        return false;
    if (f->id <= HAL_CAN_MAX_ID && proto_find(t->function, PROTO_TO_HOST) != PM_COUNT &&
        proto_find(t->function, PROTO_TO_CONTROLLER) == PM_COUNT)
        return false;

    proto_message *m = &t->m;
    const proto_error e = proto_decode(f, PROTO_TO_CONTROLLER, m);
    if (t->broadcast && !(e.reason == FW_REASON_NONE && (m->msg == PM_ESTOP || m->msg == PM_STOP)))
        return false; /* only stops are honoured from node 0, and nothing answers a broadcast */
    if (e.reason != FW_REASON_NONE) {
        fw_reject(c, t->function, range_seq(f, t->function, e), e.reason, e.field, NULL);
        return false;
    }
    t->seq = first_is_seq(m->msg) ? (uint8_t)m->v[0] : 0;
    if (m->msg == PM_TRAJ_COMMIT) {
        /* A row of a trajectory that has ended is refused as such in every state: its host learns
         * how it ended, and no row of it ever starts or joins another. */
        uint8_t field;
        int32_t where;
        const fw_reason ended = fw_rows_refusal(c, m, true, &field, &where);
        if (ended != FW_REASON_NONE) {
            fw_reject_row(c, t->function, t->seq, ended, field, where);
            return false;
        }
    }
    const fw_reason r = fw_command_allowed(m->msg, (fw_state)c->th.view.state);
    if (r != FW_REASON_NONE) {
        if (!t->broadcast)
            fw_reject(c, t->function, t->seq, r, 0, NULL);
        return false;
    }
    return true;
}

/* A command that changes only the tick's state (ENABLE, DISABLE, CLEAR_FAULT, HOME, STOP, ESTOP):
 * handed over, answered by the tick's verdict. */
static void state_command(fw_controller *c, const taken *t)
{
    if (t->m.msg == PM_ESTOP)
        fw_estop_halt(c); /* stepping halts now; the tick completes it */
    fw_handover_request(c, t->m.msg);
    const fw_verdict verdict = fw_handover(c);
    if (t->broadcast)
        return;
    if (verdict.reason != FW_REASON_NONE)
        fw_reject(c, t->function, t->seq, verdict.reason, 0, NULL);
    else
        fw_ack(c, t->function, t->seq, 0);
}

void fw_handle_frame(fw_controller *c, const hal_can_frame *f)
{
    if (c->th.boot_requested)
        return; /* restarting into the bootloader: nothing more is taken (ENABLE above all) */
    taken t;
    if (!admit(c, f, &t))
        return;
    const proto_message *m = &t.m;
    switch (m->msg) {
    case PM_HOST_HEARTBEAT:
        atomic_store(&c->sh.heartbeat_us, fw_now32(c));
        return; /* periodic: not acknowledged */
    case PM_POSE_A:
    case PM_POSE_B:
    case PM_POSE_C:
        stage(c, m, t.function);
        return; /* staging is answered by the commit */
    case PM_MOVE_COMMIT:
        move_commit(c, m, t.function);
        return;
    case PM_TRAJ_COMMIT:
        traj_commit(c, m, t.function);
        return;
    case PM_PARAM_GET:
        if (m->v[0] >= FP_COUNT) {
            fw_reject_param(c, t.function, FW_REASON_PARAM_UNKNOWN, (uint16_t)m->v[0], FW_RULE_NONE);
            return;
        }
        fw_ack(c, t.function, 0, 0);
        param_value(c, (uint16_t)m->v[0]);
        return;
    case PM_PARAM_SET:
        param_set(c, m, t.function);
        return;
    case PM_INFO_GET: /* pages 0 and 1, the ones the table lets through */
        fw_ack(c, t.function, 0, 0);
        if (m->v[0] == 0)
            info(c);
        else
            board(c);
        return;
    case PM_PARAM_SAVE:
        param_save(c, t.function);
        return;
    case PM_BOOT_ENTER:
        /* admit() judged it against the tick's state as last read, which is exact about the
         * drives: only ENABLE turns them on, and this thread hands that over and reads the state
         * it leaves.  Nothing is taken after it, so nothing can enable them before the restart. */
        fw_ack(c, t.function, t.seq, 0);
        c->th.boot_requested = true;
        return;
    case PM_ESTOP:
    case PM_STOP:
    case PM_ENABLE:
    case PM_DISABLE:
    case PM_HOME:
    case PM_CLEAR_FAULT:
        state_command(c, &t);
        return;
    default:
        fw_reject(c, t.function, t.seq, FW_REASON_UNKNOWN, 0, NULL);
        return;
    }
}
