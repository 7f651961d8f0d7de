/* Monotonic time base.  The control tick and the step interrupt are not callbacks registered
 * here: the platform's timer (an interrupt on the board, timerfd on the host) calls the
 * firmware's tick functions, so the firmware never needs to know how time is kept. */
#ifndef HAL_CLOCK_H
#define HAL_CLOCK_H

#include <stdint.h>

typedef struct {
    void *ctx;
    uint64_t (*now_us)(void *ctx); /* microseconds since an arbitrary origin; never goes back */
} hal_clock;

#endif
