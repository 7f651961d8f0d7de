/* Command handling: frames in, acknowledgements and rejects out.  Every refused command gets a
 * REJECT naming why, and nothing of it is applied. */
#include "fw/controller_internal.h"

#include <string.h>

#include "fw/reject.h"

#define A FW_REASON_NONE
#define S FW_REASON_STATE

/* Which command each state accepts.  Columns: boot, disabled, homing, idle, moving, stopping,
 * fault, estop.  Motion commands check homing and their queue on top of this. */
static const uint8_t allowed[PM_COUNT][FW_STATE_COUNT] = {
    [PM_ESTOP] = {A, A, A, A, A, A, A, A},
    [PM_STOP] = {S, A, A, A, A, A, A, A},
    [PM_HOST_HEARTBEAT] = {A, A, A, A, A, A, A, A},
    [PM_ENABLE] = {S, A, S, S, S, S, S, S},
    [PM_DISABLE] = {S, A, S, A, S, S, A, A},
    [PM_HOME] = {S, S, S, A, S, S, S, S},
    [PM_CLEAR_FAULT] = {S, S, S, S, S, S, A, A},
    [PM_POSE_A] = {S, A, A, A, A, A, A, A},
    [PM_POSE_B] = {S, A, A, A, A, A, A, A},
    [PM_POSE_C] = {S, A, A, A, A, A, A, A},
    [PM_MOVE_COMMIT] = {S, S, S, A, A, S, S, S},
    [PM_TRAJ_COMMIT] = {S, S, S, A, A, S, S, S},
    [PM_PARAM_GET] = {A, A, A, A, A, A, A, A},
    [PM_PARAM_SET] = {S, A, S, S, S, S, A, A},
    [PM_PARAM_SAVE] = {S, A, S, S, S, S, A, A},
};

#undef A
#undef S

fw_reason fw_command_allowed(proto_msg cmd, fw_state state)
{
    if ((unsigned)cmd >= PM_COUNT || (unsigned)state >= FW_STATE_COUNT ||
        proto_table[cmd].dir != PROTO_TO_CONTROLLER)
        return FW_REASON_UNKNOWN;
    return (fw_reason)allowed[cmd][state];
}

void fw_send(fw_controller *c, proto_msg msg, const int32_t *values)
{
    proto_message m;
    m.msg = msg;
    m.node = c->cfg.node;
    for (int i = 0; i < proto_table[msg].nfields; ++i)
        /* Each caller's array holds its message's nfields; the analyzer cannot see the table's.
         * NOLINTNEXTLINE(clang-analyzer-core.uninitialized.Assign) */
        m.v[i] = values[i];
    hal_can_frame f;
    if (proto_encode(&m, &f) == 0)
        c->hal.can.send(c->hal.can.ctx, &f);
}

void fw_ack(fw_controller *c, uint8_t function, uint8_t seq, uint32_t detail)
{
    const int32_t v[5] = {function, seq, (int32_t)fw_traj_depth(&c->traj),
                          (int32_t)fw_traj_free(&c->traj), (int32_t)(detail > INT32_MAX ? INT32_MAX : detail)};
    fw_send(c, PM_ACK, v);
}

void fw_reject(fw_controller *c, uint8_t function, uint8_t seq, fw_reason reason, uint8_t field,
               const fw_plan_result *why)
{
    if (reason == FW_REASON_STATE)
        field = (uint8_t)c->state; /* whichever check refused, the host learns the state it refused in */
    int32_t v[PROTO_MAX_FIELDS];
    fw_reject_values(function, seq, reason, field, why, v);
    fw_send(c, PM_REJECT, v);
}

/* Sequence numbers wrap at 256: newer means ahead by 1..127. */
static bool newer(uint8_t seq, uint8_t than)
{
    const uint8_t d = (uint8_t)(seq - than);
    return d != 0 && d < 128u;
}

static void stage(fw_controller *c, const proto_message *m, uint8_t function)
{
    const uint8_t seq = (uint8_t)m->v[0];
    /* Both refusals before anything changes: a refused part leaves the staged pose as it was. */
    if (c->any_commit && !newer(seq, c->last_seq)) {
        fw_reject(c, function, seq, FW_REASON_STALE, 0, NULL);
        return;
    }
    /* A part of another number starts the staging afresh, whichever of the two numbers is ahead:
     * parts of two numbers never mix, because a commit needs all three under its own number, and
     * a stray part staged under a number ahead of the host's (a second tool, a corrupted frame)
     * must not refuse the host's parts until a restart, as it would if it could not be displaced. */
    if (c->stage_have != 0 && seq != c->stage_seq)
        c->stage_have = 0;
    const int part = (int)m->msg - PM_POSE_A;
    c->stage_seq = seq;
    c->stage_have |= (uint8_t)(1u << part);
    c->stage_v[2 * part] = m->v[1];
    c->stage_v[2 * part + 1] = m->v[2];
}

/* The staged pose a commit of seq would move to, in SI units, or why there is none. */
static fw_reason commit_target(const fw_controller *c, uint8_t seq, tse_real pose[6])
{
    if (c->any_commit && !newer(seq, c->last_seq))
        return FW_REASON_STALE;
    if (c->stage_have != 7u || c->stage_seq != seq)
        return FW_REASON_INCOMPLETE;
    if (!c->homed)
        return FW_REASON_NOT_HOMED;
    for (int k = 0; k < 6; ++k)
        pose[k] = (tse_real)c->stage_v[k] * TSE_R(1e-6);
    return FW_REASON_NONE;
}

static void accept_commit(fw_controller *c, uint8_t seq)
{
    c->last_seq = seq;
    c->any_commit = true;
    c->stage_have = 0;
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
    const bool queued = c->state == FW_STATE_MOVING;
    if (queued && (c->src != FW_SRC_MOVE || c->stopping || c->cfg.no_blend)) {
        fw_reject(c, function, seq, FW_REASON_STATE, 0, NULL);
        return;
    }
    if (queued && c->has_next) {
        fw_reject(c, function, seq, FW_REASON_QUEUE_FULL, 0, NULL);
        return;
    }
    const fw_move_kind kind = m->v[1] == 0 ? FW_MOVE_DURATION : FW_MOVE_SPEED;
    const tse_real value = kind == FW_MOVE_DURATION ? (tse_real)m->v[2] * TSE_R(1e-3)
                                                    : (tse_real)m->v[2] * TSE_R(1e-6);
    /* A move committed during another starts from that one's end. */
    fw_move *mv = queued ? &c->next : &c->move;
    const tse_real *from = queued ? c->move.to : c->pose;
    const tse_real *q_from = queued ? c->move.q_end : c->q;
    fw_plan_result why;
    if (fw_move_plan(mv, &c->geom, &c->lim, from, to, kind, value, q_from, &why) != 0) {
        fw_reject(c, function, seq, why.reason, 0, &why);
        /* A refused pose is spent: its sequence number cannot be committed again. */
        accept_commit(c, seq);
        return;
    }
    accept_commit(c, seq);
    fw_move_start start = FW_START_REST;
    if (queued) {
        /* Blend if the path allows, else run it back to back; setpoints already queued for the
         * step generator are behind us. */
        start = fw_move_blend(&c->move, &c->next, &c->geom, &c->lim, c->segments_run + 2u, &c->blend_k0) == 0
                    ? FW_START_BLENDED
                    : FW_START_AFTER;
        c->has_next = true;
    } else {
        fw_start_source(c, FW_SRC_MOVE);
    }
    fw_ack(c, function, seq, (uint32_t)(mv->prof.T * TSE_R(1000.0) + TSE_R(0.5)));
    /* Per mille of the limit, rounded up: a demand over the limit never reads as at it. */
    const tse_real demand = mv->bound_ratio * TSE_R(1000.0);
    const int32_t info[5] = {seq, start, mv->bound, mv->bound_slide,
                             demand >= TSE_R(65535.0) ? 65535 : (int32_t)tse_ceil(demand)};
    fw_send(c, PM_MOVE_INFO, info);
}

static void traj_commit(fw_controller *c, const proto_message *m, uint8_t function)
{
    const uint8_t seq = (uint8_t)m->v[0];
    tse_real to[6];
    fw_reason r = commit_target(c, seq, to);
    if (r == FW_REASON_NONE && c->state == FW_STATE_MOVING && c->src != FW_SRC_TRAJ)
        r = FW_REASON_STATE;
    if (r != FW_REASON_NONE) {
        fw_reject(c, function, seq, r, 0, NULL);
        return;
    }
    if (c->state == FW_STATE_IDLE)
        fw_traj_start(&c->traj, &c->lim, c->pose, c->q);
    fw_plan_result why;
    if (fw_traj_push(&c->traj, &c->geom, &c->lim, to, (uint32_t)m->v[1], (m->v[2] & 1) != 0, &why) != 0) {
        fw_reject(c, function, seq, why.reason, 0, &why);
        /* Refused for its content (the pose, its timing), the number is spent, as for moves; a
         * full queue, or a trajectory that takes no more points (state), changes nothing. */
        if (why.reason != FW_REASON_QUEUE_FULL && why.reason != FW_REASON_STATE)
            accept_commit(c, seq);
        return;
    }
    accept_commit(c, seq);
    if (c->state == FW_STATE_IDLE)
        fw_start_source(c, FW_SRC_TRAJ);
    fw_ack(c, function, seq, 0);
}

static void param_value(fw_controller *c, uint16_t id)
{
    const int32_t v[2] = {id, c->params.v[id]};
    fw_send(c, PM_PARAM_VALUE, v);
}

static void param_set(fw_controller *c, const proto_message *m, uint8_t function)
{
    const uint16_t id = (uint16_t)m->v[0];
    fw_param_set next = c->params;
    const int r = fw_params_set_one(&next, id, m->v[1]);
    if (r != 0) {
        fw_reject(c, function, 0, (fw_reason)r, (uint8_t)(id > 255 ? 255 : id), NULL);
        return;
    }
    if (fw_apply_params(c, &next) != 0) {
        fw_reject(c, function, 0, FW_REASON_PARAM_SET, (uint8_t)id, NULL);
        return;
    }
    fw_ack(c, function, 0, 0);
    param_value(c, id);
}

static void param_save(fw_controller *c, uint8_t function)
{
    uint8_t buf[256];
    const size_t n = fw_params_serialize(&c->params, buf, sizeof buf);
    if (n == 0 || c->hal.storage.save(c->hal.storage.ctx, buf, n) != 0) {
        fw_reject(c, function, 0, FW_REASON_STORAGE, 0, NULL);
        return;
    }
    fw_ack(c, function, 0, 0);
}

/* The sequence number of a frame refused by the codec: a field out of range leaves its sequence
 * number the frame's (a u8, never itself out of range), and the host matches the REJECT by it; a
 * frame of another length or an unknown function has none. */
static uint8_t range_seq(const hal_can_frame *f, uint8_t function, proto_error e)
{
    const proto_def *d = proto_lookup(function, PROTO_TO_CONTROLLER);
    if (e.reason != FW_REASON_RANGE || !d || d->nfields == 0 || strcmp(d->fields[0].name, "seq") != 0)
        return 0;
    return f->data[d->fields[0].offset];
}

void fw_handle_frame(fw_controller *c, const hal_can_frame *f)
{
    /* An e-stop interrupt during the poll: no command is taken against the state before it. */
    fw_estop_complete(c);
    const uint8_t node = (uint8_t)(f->id & PROTO_NODE_MASK);
    const uint8_t function = (uint8_t)(f->id >> PROTO_NODE_BITS);
    const bool broadcast = node == PROTO_BROADCAST;
    /* Frames for other controllers, and our own kind of traffic from other nodes, are not ours. */
    if (!broadcast && node != c->cfg.node)
        return;
    if (f->id <= HAL_CAN_MAX_ID && proto_lookup(function, PROTO_TO_HOST) != NULL &&
        proto_lookup(function, PROTO_TO_CONTROLLER) == NULL)
        return;

    proto_message m;
    const proto_error e = proto_decode(f, PROTO_TO_CONTROLLER, &m);
    if (broadcast && !(e.reason == FW_REASON_NONE && (m.msg == PM_ESTOP || m.msg == PM_STOP)))
        return; /* only stops are honoured from node 0, and nothing answers a broadcast */
    if (e.reason != FW_REASON_NONE) {
        fw_reject(c, function, range_seq(f, function, e), e.reason, e.field, NULL);
        return;
    }
    const bool has_seq = proto_table[m.msg].nfields > 0 && strcmp(proto_table[m.msg].fields[0].name, "seq") == 0;
    const uint8_t seq = has_seq ? (uint8_t)m.v[0] : 0;
    const fw_reason r = fw_command_allowed(m.msg, c->state);
    if (r != FW_REASON_NONE) {
        if (!broadcast)
            fw_reject(c, function, seq, r, 0, NULL);
        return;
    }

    switch (m.msg) {
    case PM_ESTOP:
        fw_estop(c);
        break;
    case PM_STOP:
        fw_stop_motion(c);
        break;
    case PM_HOST_HEARTBEAT:
        c->last_heartbeat_us = c->hal.clock.now_us(c->hal.clock.ctx);
        return; /* periodic: not acknowledged */
    case PM_ENABLE:
        fw_drives(c, true);
        c->last_heartbeat_us = c->hal.clock.now_us(c->hal.clock.ctx);
        fw_set_state(c, FW_STATE_IDLE);
        break;
    case PM_DISABLE:
        if (c->state == FW_STATE_IDLE) {
            fw_drives(c, false);
            fw_set_state(c, FW_STATE_DISABLED);
        }
        break;
    case PM_HOME:
        fw_homing_start(c);
        break;
    case PM_CLEAR_FAULT:
        if (c->hal.inputs.estop(c->hal.inputs.ctx)) {
            /* The input still open: it would latch again at once.  The reject says the state. */
            fw_reject(c, function, seq, FW_REASON_STATE, 0, NULL);
            return;
        }
        c->fault = FW_FAULT_NONE;
        c->pending_fault = FW_FAULT_NONE;
        fw_drives(c, false);
        fw_set_state(c, FW_STATE_DISABLED);
        break;
    case PM_POSE_A:
    case PM_POSE_B:
    case PM_POSE_C:
        stage(c, &m, function);
        return; /* staging is answered by the commit */
    case PM_MOVE_COMMIT:
        move_commit(c, &m, function);
        return;
    case PM_TRAJ_COMMIT:
        traj_commit(c, &m, function);
        return;
    case PM_PARAM_GET:
        if (m.v[0] >= FP_COUNT) {
            fw_reject(c, function, 0, FW_REASON_PARAM_UNKNOWN, (uint8_t)(m.v[0] > 255 ? 255 : m.v[0]), NULL);
            return;
        }
        fw_ack(c, function, 0, 0);
        param_value(c, (uint16_t)m.v[0]);
        return;
    case PM_PARAM_SET:
        param_set(c, &m, function);
        return;
    case PM_PARAM_SAVE:
        param_save(c, function);
        return;
    default:
        fw_reject(c, function, seq, FW_REASON_UNKNOWN, 0, NULL);
        return;
    }
    if (!broadcast)
        fw_ack(c, function, seq, 0);
}
