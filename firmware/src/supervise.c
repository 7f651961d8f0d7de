#include "supervise.h"

#include "state.h"
#include "steps.h"

/* What the switches say against what the controller believes: a high-end switch pressed, or, once
 * homed and outside homing, a low switch pressed clearly above its position or released clearly
 * below it (the step count and the switch disagree: lost steps, or a broken switch). */
static bool switches_disagree(const fw_controller *c, uint16_t pressed)
{
    const fw_tick *t = &c->tick;
    if (pressed & 0x3F00u)
        return true;
    if (!t->homed || t->home.active)
        return false;
    int32_t pos[STEPGEN_AXES];
    stepgen_positions(&c->sg, pos);
    const int32_t tol = fw_steps_of_um(&t->params, FW_HOME_SW_TOLERANCE_UM);
    for (int k = 0; k < 6; ++k) {
        const int32_t sw = fw_switch_steps(&t->params, k);
        const bool on = (pressed >> k) & 1u;
        if ((on && pos[k] > sw + tol) || (!on && pos[k] < sw - tol))
            return true;
    }
    return false;
}

void fw_supervise(fw_controller *c)
{
    fw_tick *t = &c->tick;
    t->estop_in = c->hal.inputs.estop(c->hal.inputs.ctx);
    t->switches_off = switches_disagree(c, c->hal.inputs.limits(c->hal.inputs.ctx));
    hal_can_state cs;
    c->hal.can.state(c->hal.can.ctx, &cs);
    t->error_passive = cs.error_passive;
    if (t->state == FW_STATE_BOOT)
        return;
    if (t->estop_in) {
        if (t->state != FW_STATE_ESTOP)
            fw_estop(c);
        return;
    }
    const bool active = t->state == FW_STATE_IDLE || t->state == FW_STATE_MOVING ||
                        t->state == FW_STATE_STOPPING || t->state == FW_STATE_HOMING;
    if (!t->home.active && active && t->switches_off) {
        t->homed = false; /* the step count is not to be trusted any more */
        fw_fault_raise(c, FW_FAULT_LIMIT);
    }
    /* A bus-off that recovered since the last look counts as much as one that lasts. */
    const bool went_bus_off = cs.bus_off_events != t->bus_off_seen;
    t->bus_off_seen = cs.bus_off_events;
    if ((cs.bus_off || went_bus_off) && t->state != FW_STATE_FAULT)
        fw_fault_raise(c, FW_FAULT_BUS_OFF);
    /* A segment the generator could not step in its time: the slides fell out of step with each
     * other and with the path, so the motion stops under control and the fault latches. */
    const uint32_t overruns = c->sg.overruns;
    if (overruns != t->overruns_seen) {
        t->overruns_seen = overruns;
        fw_fault_raise(c, FW_FAULT_STEP_OVERRUN);
    }
    /* The host is silent when no heartbeat came for watchdog_ms up to the last time the thread
     * found the bus empty, not up to now: heartbeats still waiting on the bus, unread because the
     * thread has not run since (the simulator's tick thread making up late periods on a starved
     * host before its main thread runs), are not silence.  A thread that never reads the bus again
     * is the board's hardware watchdog's to catch (fw_thread_progress).  bus_read_us first: a
     * heartbeat the thread took before it is then seen too.  Signed: ENABLE's heartbeat, stored by
     * the tick, may be newer than the last look. */
    const uint32_t wd = (uint32_t)t->params.v[FP_WATCHDOG_MS];
    const uint32_t looked = atomic_load(&c->sh.bus_read_us);
    const int32_t silent = (int32_t)(looked - atomic_load(&c->sh.heartbeat_us));
    if (wd > 0 && t->drives_on && silent > (int32_t)(wd * 1000u))
        fw_fault_raise(c, FW_FAULT_WATCHDOG);
}
