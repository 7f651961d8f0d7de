/* The two periodic events that drive the firmware: the control tick (segment rate, >= 1 kHz) and
 * the step interrupt (step rate, a multiple of it).  On the board these are timer interrupts; in
 * the simulator, timerfd-driven calls.  The application's main starts them with the firmware's
 * fw_control_tick and fw_step_tick; the firmware itself never starts a timer. */
#ifndef HAL_TICKER_H
#define HAL_TICKER_H

#include <stdint.h>

typedef struct {
    void *ctx;
    /* Calls control(arg) control_hz times a second and step(arg) step_hz times a second until
     * stop; step takes precedence when both are due.  Returns 0, or -1 for rates the hardware
     * cannot keep. */
    int (*start)(void *ctx, uint32_t control_hz, void (*control)(void *arg), uint32_t step_hz,
                 void (*step)(void *arg), void *arg);
    void (*stop)(void *ctx);
} hal_ticker;

#endif
