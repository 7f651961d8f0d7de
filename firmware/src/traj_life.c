#include "traj_life.h"

#include "publish.h"

/* REJECT `ended` carries the fault in the field's high four bits. */
_Static_assert(FW_FAULT_COUNT <= 16 && FW_TRAJ_END_COUNT <= 16, "ended: how and fault share a byte");

void fw_traj_life_open(fw_controller *c, uint8_t id)
{
    fw_tick *t = &c->tick;
    fw_traj_queue_start(&t->traj, t->pose);
    t->traj_open = true;
    t->traj_clock = false;
    t->traj_id = id;
    t->traj_rows = 0;
}

fw_reason fw_traj_life_row(fw_controller *c, const fw_traj_point *p)
{
    fw_tick *t = &c->tick;
    if (!t->traj_open)
        return FW_REASON_ENDED;
    fw_reason why;
    if (fw_traj_queue_push(&t->traj, p, &why) != 0)
        return why;
    ++t->traj_rows;
    return FW_REASON_NONE;
}

bool fw_traj_life_priming(fw_controller *c)
{
    fw_tick *t = &c->tick;
    if (!t->traj_open || t->traj_clock)
        return false; /* running, or ended and being stopped along what it held */
    /* While the queue fills the plate is at rest: waiting is safe (the watchdog still watches the
     * host).  A queue that fills before the lead would wait for ever: it starts the clock too. */
    if (t->traj.end_us < (uint64_t)t->params.v[FP_TRAJ_LEAD] && !t->traj.closed && fw_traj_queue_free(&t->traj) > 0)
        return true;
    t->traj_clock = true;
    t->tau = TSE_R(0.0);
    t->segments_run = 0;
    return false;
}

void fw_traj_life_end(fw_controller *c, fw_traj_end how, fw_fault f)
{
    fw_tick *t = &c->tick;
    if (!t->traj_open)
        return;
    t->traj_open = false;
    const fw_traj_ended e = {t->traj_id, (uint8_t)how, (uint8_t)(how == FW_TRAJ_END_FAULT ? f : FW_FAULT_NONE),
                             t->traj_rows, fw_now(c)};
    fw_ended_post(c, &e);
}

void fw_traj_life_end_pending(fw_controller *c, fw_traj_end otherwise)
{
    if (c->tick.pending_fault != FW_FAULT_NONE)
        fw_traj_life_end(c, FW_TRAJ_END_FAULT, c->tick.pending_fault);
    else
        fw_traj_life_end(c, otherwise, FW_FAULT_NONE);
}
