#include "hal_fault/fault_stepper.h"

#include <string.h>

void fault_stepper_init(fault_stepper *fs, const fault_stepper_config *cfg, hal_stepper inner, hal_clock clock)
{
    memset(fs, 0, sizeof *fs);
    fs->cfg = *cfg;
    fs->inner = inner;
    fs->forward = 0x3F; /* until the first set_dir, as a fresh step generator assumes */
    fault_clock_init(&fs->clock, clock);
}

static void set_dir(void *ctx, uint8_t mask)
{
    fault_stepper *fs = ctx;
    fs->forward = mask;
    fs->inner.set_dir(fs->inner.ctx, mask);
}

static void pulse(void *ctx, uint8_t mask)
{
    fault_stepper *fs = ctx;
    uint8_t lose = 0;
    if ((mask & fs->cfg.stall_mask) && fault_window_holds(&fs->cfg.stall, fault_clock_us(&fs->clock)))
        lose = mask & fs->cfg.stall_mask;
    for (int k = 0; k < HAL_AXES; ++k) {
        const uint8_t bit = (uint8_t)(1u << k);
        if ((mask & bit) && !(lose & bit) && fs->cfg.miss[k] > 0) {
            --fs->cfg.miss[k];
            lose |= bit;
        }
        if (lose & bit) {
            fs->lost[k] += (fs->forward & bit) ? 1 : -1;
            ++fs->lost_total;
        }
    }
    if (mask & (uint8_t)~lose)
        fs->inner.pulse(fs->inner.ctx, mask & (uint8_t)~lose);
}

static void enable(void *ctx, bool on)
{
    fault_stepper *fs = ctx;
    fs->inner.enable(fs->inner.ctx, on);
}

static void timing(void *ctx, uint32_t pulse_ns, uint32_t dir_setup_ns)
{
    fault_stepper *fs = ctx;
    fs->inner.timing(fs->inner.ctx, pulse_ns, dir_setup_ns);
}

hal_stepper fault_stepper_hal(fault_stepper *fs)
{
    return (hal_stepper){fs, set_dir, pulse, enable, fs->inner.timing ? timing : NULL};
}
