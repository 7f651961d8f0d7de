#include "fw/runtime.h"

#include "commands.h"
#include "control.h"
#include "controller_internal.h"
#include "homing.h"
#include "inbox.h"
#include "publish.h"
#include "state.h"
#include "telemetry.h"
#include "traj_rows.h"

void fw_step_tick(fw_controller *c)
{
    const stepgen_output o = stepgen_tick(&c->sg);
    if (o.dir_changed)
        c->hal.stepper.set_dir(c->hal.stepper.ctx, o.forward_mask);
    if (o.step_mask)
        c->hal.stepper.pulse(c->hal.stepper.ctx, o.step_mask);
}

void fw_control_tick(fw_controller *c)
{
    fw_control_run(c);
}

void fw_poll(fw_controller *c)
{
    atomic_fetch_add_explicit(&c->sh.progress, 1u, memory_order_relaxed);
    /* Homing's path check, if the tick waits for it (not in the tick: homing.h). */
    fw_homing_check_path(c);
    fw_view_read(c);
    /* How a trajectory ended goes out before any row of the next is taken. */
    fw_rows_collect(c);
    hal_can_frame f;
    while (fw_inbox_next(c, &f)) {
        fw_view_read(c);
        fw_handle_frame(c, &f);
        fw_rows_collect(c);
    }
    fw_view_read(c);
    fw_telemetry_poll(c);
}

void fw_estop_isr(fw_controller *c)
{
    fw_estop_halt(c);
}

uint32_t fw_thread_progress(const fw_controller *c)
{
    return atomic_load_explicit(&c->sh.progress, memory_order_relaxed);
}

static void ran(fw_ran_hook hook, void *ctx, fw_ran what)
{
    if (hook)
        hook(ctx, what);
}

void fw_period_start(fw_controller *c, fw_ran_hook hook, void *ctx)
{
    fw_poll(c);
    ran(hook, ctx, FW_RAN_POLL);
    fw_control_tick(c);
    ran(hook, ctx, FW_RAN_CONTROL);
}

void fw_run_period(fw_controller *c, fw_ran_hook hook, void *ctx)
{
    fw_period_start(c, hook, ctx);
    const uint32_t steps = c->cfg.step_hz / c->cfg.segment_hz;
    for (uint32_t s = 0; s < steps; ++s) {
        fw_step_tick(c);
        ran(hook, ctx, FW_RAN_STEP);
    }
}
