/* Step, direction and enable outputs of the six slide drivers.
 *
 * Called from the step interrupt: set_dir before pulse whenever a direction changes (the step
 * generator keeps the driver's direction set-up time), then pulse raises STEP on the axes of the
 * mask; the implementation ends the pulse after the configured pulse width. */
#ifndef HAL_STEPPER_H
#define HAL_STEPPER_H

#include <stdbool.h>
#include <stdint.h>

#define HAL_AXES 6

typedef struct {
    void *ctx;
    void (*set_dir)(void *ctx, uint8_t forward_mask); /* bit i set: axis i moves towards +s */
    void (*pulse)(void *ctx, uint8_t step_mask);
    void (*enable)(void *ctx, bool on);               /* shared ENABLE of all six drivers */
} hal_stepper;

#endif
