#include "handover.h"

#include <string.h>

#include "adopt.h"
#include "fw/command_table.h"
#include "homing.h"
#include "inbox.h"
#include "motion.h"
#include "publish.h"
#include "state.h"
#include "traj_life.h"

fw_request *fw_handover_request(fw_controller *c, proto_msg msg)
{
    fw_request *r = &c->sh.req;
    r->msg = msg;
    r->judged = c->th.view.state;
    return r;
}

fw_verdict fw_handover(fw_controller *c)
{
    fw_shared *s = &c->sh;
    const uint32_t n = atomic_load_explicit(&s->posted, memory_order_relaxed) + 1u;
    atomic_store_explicit(&s->posted, n, memory_order_release);
    if (!c->cfg.await)
        fw_handover_take(c);
    else
        while (atomic_load_explicit(&s->taken, memory_order_acquire) != n) {
            c->cfg.await(c->cfg.await_ctx);
            fw_inbox_look(c); /* the host's heartbeats go on meanwhile */
        }
    const fw_verdict v = s->verdict;
    fw_view_read(c);
    return v;
}

static bool same_pose(const tse_real a[6], const tse_real b[6])
{
    for (int k = 0; k < 6; ++k)
        if (a[k] != b[k])
            return false;
    return true;
}

static fw_reason take_move(fw_controller *c, const fw_request *r, fw_move_start *start)
{
    fw_tick *t = &c->tick;
    if (!t->homed)
        return FW_REASON_NOT_HOMED;
    const fw_move *mv = &r->u.move.mv;
    if (r->u.move.successor) {
        *start = fw_motion_join(c, mv, r->u.move.blend, r->u.move.k0);
        if (*start != FW_START_COUNT)
            return FW_REASON_NONE;
        /* The running move ended while its successor was validated: if it ended where the
         * successor starts (not stopped short), that was planned from rest there. */
        if (t->state != FW_STATE_IDLE || t->src != FW_SRC_NONE || !t->pose_known || !same_pose(t->pose, mv->from))
            return FW_REASON_STATE;
    } else if (t->state != FW_STATE_IDLE || t->src != FW_SRC_NONE) {
        return FW_REASON_STATE;
    }
    t->move = *mv;
    fw_motion_start(c, FW_SRC_MOVE);
    *start = FW_START_REST;
    return FW_REASON_NONE;
}

static fw_reason take_row(fw_controller *c, const fw_request *r)
{
    fw_tick *t = &c->tick;
    if (!r->u.row.first)
        return fw_traj_life_row(c, &r->u.row.p);
    if (t->state != FW_STATE_IDLE || t->src != FW_SRC_NONE)
        return FW_REASON_STATE;
    fw_traj_life_open(c, r->u.row.id);
    const fw_reason why = fw_traj_life_row(c, &r->u.row.p);
    if (why == FW_REASON_NONE)
        fw_motion_start(c, FW_SRC_TRAJ);
    return why;
}

static void apply(fw_controller *c, const fw_request *r, fw_verdict *v)
{
    switch (r->msg) {
    case PM_ESTOP:
        fw_estop(c);
        break;
    case PM_STOP:
        fw_motion_stop(c);
        break;
    case PM_ENABLE:
        v->reason = fw_state_enable(c);
        break;
    case PM_DISABLE:
        v->reason = fw_state_disable(c);
        break;
    case PM_CLEAR_FAULT:
        v->reason = fw_state_clear(c);
        break;
    case PM_HOME:
        fw_homing_start(c);
        break;
    case PM_MOVE_COMMIT:
        v->reason = take_move(c, r, &v->start);
        break;
    case PM_TRAJ_COMMIT:
        v->reason = take_row(c, r);
        break;
    case PM_PARAM_SET:
        v->rule = fw_params_adopt(c, &r->u.params);
        if (v->rule != FW_RULE_NONE)
            v->reason = FW_REASON_PARAM_SET;
        break;
    default:
        v->reason = FW_REASON_UNKNOWN;
        break;
    }
}

void fw_handover_take(fw_controller *c)
{
    fw_shared *s = &c->sh;
    const uint32_t n = atomic_load_explicit(&s->posted, memory_order_acquire);
    if (n == atomic_load_explicit(&s->taken, memory_order_relaxed))
        return;
    /* An e-stop before the command: the command meets its state. */
    fw_estop_complete(c);
    fw_verdict v;
    memset(&v, 0, sizeof v);
    v.start = FW_START_REST;
    v.reason = fw_command_allowed(s->req.msg, c->tick.state);
    /* CLEAR_FAULT clears only what its sender could have seen: an e-stop that latched after the
     * thread judged it (its interrupt between the thread's look and the hand-over, completed just
     * now or by the tick meanwhile) stays, and shows, until a CLEAR_FAULT sent after it. */
    if (s->req.msg == PM_CLEAR_FAULT && c->tick.state == FW_STATE_ESTOP && s->req.judged != FW_STATE_ESTOP)
        v.reason = FW_REASON_STATE;
    /* A row of a trajectory the tick ended (its rows ran out, a fault) after the thread judged the
     * row: refused `ended` whatever the state it left (docs/protocol.md), as the thread refuses
     * the rows that come after it; the thread says how it ended. */
    if (s->req.msg == PM_TRAJ_COMMIT && !s->req.u.row.first && !c->tick.traj_open)
        v.reason = FW_REASON_ENDED;
    if (v.reason == FW_REASON_NONE)
        apply(c, &s->req, &v);
    s->verdict = v;
    fw_publish(c);
    atomic_store_explicit(&s->taken, n, memory_order_release);
}
