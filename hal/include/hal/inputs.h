/* Limit switches and the emergency stop input. */
#ifndef HAL_INPUTS_H
#define HAL_INPUTS_H

#include <stdbool.h>
#include <stdint.h>

typedef struct {
    void *ctx;
    /* Bit i: slide i's homing switch is pressed (a reference in the lower part of the stroke, not
     * an end of travel: pressed at and below the firmware's home_sw_i, released above).
     * Bit 8 + i: the optional switch at the high end of the stroke. */
    uint16_t (*limits)(void *ctx);
    bool (*estop)(void *ctx); /* true while the e-stop circuit is open */
} hal_inputs;

#endif
