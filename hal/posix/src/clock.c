/* The monotonic clock of hal/posix (posix_hal.h). */
#define _POSIX_C_SOURCE 200809L
#include <time.h>

#include "hal_posix/posix_hal.h"

static uint64_t now_us(void *ctx)
{
    (void)ctx;
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (uint64_t)t.tv_sec * 1000000u + (uint64_t)t.tv_nsec / 1000u;
}

hal_clock posix_clock_hal(void)
{
    return (hal_clock){NULL, now_us};
}
