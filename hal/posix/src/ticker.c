#define _GNU_SOURCE
#include <stdint.h>
#include <sys/timerfd.h>
#include <time.h>
#include <unistd.h>

#include "hal_posix/posix_hal.h"

static int start(void *ctx, uint32_t control_hz, void (*control)(void *), uint32_t step_hz, void (*step)(void *),
                 void *arg)
{
    posix_ticker *t = ctx;
    if (control_hz == 0 || step_hz % control_hz != 0 || 1000000000u % control_hz != 0)
        return -1;
    const int fd = timerfd_create(CLOCK_MONOTONIC, 0);
    if (fd < 0)
        return -1;
    const long period_ns = (long)(1000000000u / control_hz);
    struct itimerspec its = {{0, period_ns}, {0, period_ns}};
    if (timerfd_settime(fd, 0, &its, NULL) < 0) {
        close(fd);
        return -1;
    }
    const uint32_t steps = step_hz / control_hz;
    while (!t->stop) {
        uint64_t expirations = 0;
        if (read(fd, &expirations, sizeof expirations) != (ssize_t)sizeof expirations)
            continue; /* a signal: check stop */
        if (expirations > 1)
            t->overruns += expirations - 1;
        if (expirations > t->max_behind)
            t->max_behind = expirations;
        t->periods += expirations;
        /* Late periods are made up, so simulated time keeps pace with the wall clock. */
        for (uint64_t e = 0; e < expirations && !t->stop; ++e) {
            control(arg);
            for (uint32_t s = 0; s < steps; ++s)
                step(arg);
        }
    }
    close(fd);
    return 0;
}

static void stop(void *ctx)
{
    ((posix_ticker *)ctx)->stop = 1;
}

hal_ticker posix_ticker_hal(posix_ticker *t)
{
    return (hal_ticker){t, start, stop};
}
