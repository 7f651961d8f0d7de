#include "hal_fault/fault_inputs.h"

void fault_inputs_init(fault_inputs *fi, const fault_inputs_config *cfg, hal_inputs inner, hal_clock clock)
{
    fi->cfg = *cfg;
    fi->inner = inner;
    fault_clock_init(&fi->clock, clock);
}

static uint16_t limits(void *ctx)
{
    fault_inputs *fi = ctx;
    uint16_t m = fi->inner.limits(fi->inner.ctx);
    if (fault_window_holds(&fi->cfg.limit, fault_clock_us(&fi->clock)))
        m |= fi->cfg.limit_mask;
    return m;
}

static bool estop(void *ctx)
{
    fault_inputs *fi = ctx;
    return fi->inner.estop(fi->inner.ctx) || fault_window_holds(&fi->cfg.estop, fault_clock_us(&fi->clock));
}

hal_inputs fault_inputs_hal(fault_inputs *fi)
{
    return (hal_inputs){fi, limits, estop};
}
