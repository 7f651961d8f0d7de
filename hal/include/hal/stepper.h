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
    /* Shared ENABLE of all six drivers.  enable(ctx, false) must be safe from an interrupt of any
     * priority (the e-stop interrupt switches the drives off through it). */
    void (*enable)(void *ctx, bool on);
    /* The drivers' timing, whenever the controller adopts a parameter set (at start-up and on
     * every accepted change): pulse_ns is the STEP high time the implementation must produce;
     * dir_setup_ns is how long DIR is stable before a STEP edge, which the step generator already
     * keeps in whole step interrupts (for implementations that check or time it).  Called from the
     * main loop, with the step generator at rest.  May be NULL. */
    void (*timing)(void *ctx, uint32_t pulse_ns, uint32_t dir_setup_ns);
} hal_stepper;

#endif
