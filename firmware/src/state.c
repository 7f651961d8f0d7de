#include "state.h"

#include "motion.h"
#include "traj_life.h"

void fw_drives(fw_controller *c, bool on)
{
    c->tick.drives_on = on;
    c->hal.stepper.enable(c->hal.stepper.ctx, on);
    /* An e-stop just before the enable would be undone by it: look after it.  Either the request
     * shows here, or the e-stop's own switch-off comes after ours. */
    if (on && atomic_load(&c->sh.estop_request)) {
        c->tick.drives_on = false;
        c->hal.stepper.enable(c->hal.stepper.ctx, false);
    }
}

void fw_estop_halt(fw_controller *c)
{
    /* Stepping first: it is what must stop at once.  The request last, so that whoever completes
     * it finds the halt already in place. */
    stepgen_halt(&c->sg);
    c->hal.stepper.enable(c->hal.stepper.ctx, false);
    atomic_store(&c->sh.estop_request, true);
}

void fw_estop(fw_controller *c)
{
    fw_tick *t = &c->tick;
    /* Stepping ends now, not after a ramp: the queued segments go too. */
    stepgen_abort(&c->sg);
    fw_drives(c, false);
    t->src = FW_SRC_NONE;
    t->has_next = false;
    t->stopping = false;
    t->home.active = false;
    t->homed = false; /* steps may have been lost under the abrupt stop: home again */
    t->pose_known = false;
    fw_traj_queue_drop(&t->traj);
    fw_traj_life_end(c, FW_TRAJ_END_FAULT, FW_FAULT_ESTOP);
    t->fault = FW_FAULT_ESTOP;
    t->pending_fault = FW_FAULT_NONE;
    fw_set_state(c, FW_STATE_ESTOP);
}

void fw_estop_complete(fw_controller *c)
{
    if (atomic_exchange(&c->sh.estop_request, false))
        fw_estop(c);
}

static void latch_fault(fw_controller *c, fw_fault f)
{
    fw_tick *t = &c->tick;
    fw_traj_life_end(c, FW_TRAJ_END_FAULT, f);
    t->fault = f;
    t->pending_fault = FW_FAULT_NONE;
    t->src = FW_SRC_NONE;
    t->has_next = false;
    t->stopping = false;
    t->home.active = false;
    fw_traj_queue_drop(&t->traj);
    fw_drives(c, false);
    fw_set_state(c, FW_STATE_FAULT);
}

void fw_fault_raise(fw_controller *c, fw_fault f)
{
    fw_tick *t = &c->tick;
    if (t->state == FW_STATE_FAULT || t->state == FW_STATE_ESTOP)
        return;
    if (t->state == FW_STATE_MOVING || t->state == FW_STATE_STOPPING || t->state == FW_STATE_HOMING) {
        if (t->pending_fault == FW_FAULT_NONE)
            t->pending_fault = f;
        fw_motion_stop(c);
        return;
    }
    latch_fault(c, f);
}

void fw_state_at_rest(fw_controller *c)
{
    fw_tick *t = &c->tick;
    if (t->pending_fault != FW_FAULT_NONE)
        latch_fault(c, t->pending_fault);
    else
        fw_set_state(c, FW_STATE_IDLE);
}

fw_reason fw_state_enable(fw_controller *c)
{
    fw_drives(c, true);
    atomic_store(&c->sh.heartbeat_us, fw_now32(c));
    fw_set_state(c, FW_STATE_IDLE);
    return FW_REASON_NONE;
}

fw_reason fw_state_disable(fw_controller *c)
{
    if (c->tick.state == FW_STATE_IDLE) {
        fw_drives(c, false);
        fw_set_state(c, FW_STATE_DISABLED);
    }
    return FW_REASON_NONE;
}

fw_reason fw_state_clear(fw_controller *c)
{
    if (c->hal.inputs.estop(c->hal.inputs.ctx))
        return FW_REASON_STATE; /* the input still open: it would latch again at once */
    c->tick.fault = FW_FAULT_NONE;
    c->tick.pending_fault = FW_FAULT_NONE;
    fw_drives(c, false);
    fw_set_state(c, FW_STATE_DISABLED);
    return FW_REASON_NONE;
}
