/* A hal_stepper between the controller and the drives (the plant) whose slides can fail to take
 * the steps they are given: a stalled slide within a window of time, or a slide that misses its
 * next few steps.  Direction, enable and timing pass through unchanged.  The steps not taken are
 * counted per slide with their sign, so that a test knows exactly where the slides truly are
 * against what the controller emitted: emitted = taken + lost. */
#ifndef HAL_FAULT_STEPPER_H
#define HAL_FAULT_STEPPER_H

#include <stdint.h>

#include "hal/clock.h"
#include "hal/stepper.h"
#include "hal_fault/fault_time.h"

typedef struct {
    fault_window stall;       /* the slides of stall_mask take no step */
    uint8_t stall_mask;       /* bit i: slide i */
    uint32_t miss[HAL_AXES];  /* slide i misses its next miss[i] steps (counted down as it does) */
} fault_stepper_config;

typedef struct {
    fault_stepper_config cfg; /* may be changed between calls */
    hal_stepper inner;
    fault_clock clock;
    uint8_t forward;          /* the direction last set */
    int64_t lost[HAL_AXES];   /* steps not taken, + for those towards +s */
    uint64_t lost_total;
} fault_stepper;

/* Wraps inner; the stall window's time starts now on clock. */
void fault_stepper_init(fault_stepper *fs, const fault_stepper_config *cfg, hal_stepper inner, hal_clock clock);
hal_stepper fault_stepper_hal(fault_stepper *fs);

#endif
