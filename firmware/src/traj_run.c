/* A streamed trajectory's life: which rows join it, when its clock starts, how it ended.  See
 * fw_traj_run in fw/controller.h. */
#include "fw/controller_internal.h"

/* REJECT `ended` carries the fault in the field's high four bits. */
_Static_assert(FW_FAULT_COUNT <= 16 && FW_TRAJ_END_COUNT <= 16, "ended: how and fault share a byte");

static uint64_t now_us(const fw_controller *c)
{
    return c->hal.clock.now_us(c->hal.clock.ctx);
}

void fw_traj_run_took(fw_controller *c, uint8_t seq, bool first, uint8_t id)
{
    fw_traj_run *r = &c->run;
    if (first) {
        r->open = true;
        r->clock = false;
        r->id = id;
        r->rows = 0;
    }
    ++r->rows;
    r->next_seq = (uint8_t)(seq + 1u);
}

bool fw_traj_run_priming(fw_controller *c)
{
    fw_traj_run *r = &c->run;
    if (!r->open || r->clock)
        return false; /* running, or ended and being stopped along what it held */
    /* While the queue fills the plate is at rest: waiting is safe (the watchdog still watches the
     * host).  A queue that fills before the lead would wait for ever: it starts the clock too. */
    if (fw_traj_end_us(&c->traj) < (uint64_t)c->params.v[FP_TRAJ_LEAD] && !c->traj.closed &&
        fw_traj_free(&c->traj) > 0)
        return true;
    r->clock = true;
    c->tau = TSE_R(0.0);
    c->segments_run = 0;
    return false;
}

void fw_traj_run_end(fw_controller *c, fw_traj_end how, fw_fault f)
{
    fw_traj_run *r = &c->run;
    if (!r->open)
        return;
    r->open = false;
    r->ended = how;
    r->fault = how == FW_TRAJ_END_FAULT ? f : FW_FAULT_NONE;
    r->ended_id = r->id;
    r->ended_rows = r->rows;
    r->ended_us = now_us(c);
    r->report = true;
}

void fw_traj_run_end_pending(fw_controller *c, fw_traj_end otherwise)
{
    if (c->pending_fault != FW_FAULT_NONE)
        fw_traj_run_end(c, FW_TRAJ_END_FAULT, c->pending_fault);
    else
        fw_traj_run_end(c, otherwise, FW_FAULT_NONE);
}

fw_reason fw_traj_row_refusal(const fw_controller *c, const proto_message *m, bool ended_only, uint8_t *field,
                              int32_t *where)
{
    const fw_traj_run *r = &c->run;
    const uint8_t seq = (uint8_t)m->v[0], id = (uint8_t)m->v[3];
    *field = 0;
    *where = 0;
    if (m->v[2] & PROTO_TRAJ_FIRST)
        return FW_REASON_NONE; /* a first row begins a trajectory: the state decides */
    if (r->open && id == r->id) {
        if (ended_only || seq == r->next_seq)
            return FW_REASON_NONE;
        *field = r->next_seq;
        return FW_REASON_ORDER;
    }
    if (r->ended != FW_TRAJ_END_NONE && id == r->ended_id) {
        /* For an underrun, the time since it is how late the host was with this row. */
        const uint64_t ms = (now_us(c) - r->ended_us) / 1000u;
        *field = (uint8_t)(r->ended + 16u * (unsigned)r->fault);
        *where = ms > 65535u ? 65535 : (int32_t)ms;
        return FW_REASON_ENDED;
    }
    return ended_only ? FW_REASON_NONE : FW_REASON_ENDED; /* no trajectory of that identity runs */
}

void fw_traj_run_report(fw_controller *c)
{
    fw_traj_run *r = &c->run;
    if (!r->report)
        return;
    r->report = false;
    const int32_t v[4] = {r->ended_id, r->ended, r->fault,
                          (int32_t)(r->ended_rows > 16777215u ? 16777215u : r->ended_rows)};
    fw_send(c, PM_TRAJ_END, v);
}
