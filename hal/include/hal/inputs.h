/* Limit switches and the emergency stop input. */
#ifndef HAL_INPUTS_H
#define HAL_INPUTS_H

#include <stdbool.h>
#include <stdint.h>

typedef struct {
    void *ctx;
    /* Bit i: slide i's switch at the low end of its stroke (the homing switch) is pressed.
     * Bit 8 + i: the optional switch at the high end. */
    uint16_t (*limits)(void *ctx);
    bool (*estop)(void *ctx); /* true while the e-stop circuit is open */
} hal_inputs;

#endif
