/* Monotonic time base (watchdog, telemetry periods).  The periodic events that drive the
 * firmware are hal/ticker.h's. */
#ifndef HAL_CLOCK_H
#define HAL_CLOCK_H

#include <stdint.h>

typedef struct {
    void *ctx;
    uint64_t (*now_us)(void *ctx); /* microseconds since an arbitrary origin; never goes back */
} hal_clock;

#endif
