#define _GNU_SOURCE
#include <poll.h>
#include <signal.h>
#include <sys/eventfd.h>
#include <stdint.h>
#include <sys/timerfd.h>
#include <time.h>
#include <unistd.h>

#include "hal_posix/posix_hal.h"

static void *tick_thread(void *arg)
{
    posix_ticker *t = arg;
    while (!atomic_load(&t->stop)) {
        uint64_t expirations = 0;
        if (read(t->fd, &expirations, sizeof expirations) != (ssize_t)sizeof expirations)
            continue;
        if (expirations > 1)
            t->overruns += expirations - 1;
        if (expirations > t->max_behind)
            t->max_behind = expirations;
        t->periods += expirations;
        /* Late periods are made up, so simulated time keeps pace with the wall clock. */
        for (uint64_t e = 0; e < expirations && !atomic_load(&t->stop); ++e) {
            t->control(t->arg);
            const uint64_t one = 1;
            if (write(t->efd, &one, sizeof one) < 0) {
                /* the counter is full: the waiter has plenty to read */
            }
            for (uint32_t s = 0; s < t->steps; ++s)
                t->step(t->arg);
        }
    }
    return NULL;
}

int posix_ticker_start(posix_ticker *t, uint32_t control_hz, void (*control)(void *arg), uint32_t step_hz,
                       void (*step)(void *arg), void *arg)
{
    t->fd = -1;
    if (control_hz == 0 || step_hz % control_hz != 0 || 1000000000u % control_hz != 0)
        return -1;
    atomic_store(&t->stop, 0);
    t->periods = t->overruns = t->max_behind = 0;
    t->control_hz = control_hz;
    t->steps = step_hz / control_hz;
    t->control = control;
    t->step = step;
    t->arg = arg;
    t->efd = eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK);
    if (t->efd < 0)
        return -1;
    t->fd = timerfd_create(CLOCK_MONOTONIC, 0);
    if (t->fd < 0) {
        close(t->efd);
        return -1;
    }
    const long period_ns = (long)(1000000000u / control_hz);
    struct itimerspec its = {{0, period_ns}, {0, period_ns}};
    sigset_t all, old;
    sigfillset(&all);
    /* The thread inherits the mask: every signal stays with the caller's thread. */
    pthread_sigmask(SIG_SETMASK, &all, &old);
    const int rc = timerfd_settime(t->fd, 0, &its, NULL) == 0 ? pthread_create(&t->thread, NULL, tick_thread, t) : -1;
    pthread_sigmask(SIG_SETMASK, &old, NULL);
    if (rc != 0) {
        close(t->fd);
        close(t->efd);
        t->fd = -1;
        return -1;
    }
    return 0;
}

void posix_ticker_await(posix_ticker *t)
{
    struct pollfd p = {t->efd, POLLIN, 0};
    if (poll(&p, 1, 2) > 0) { /* a control call comes every period: 2 ms is a margin, not a wait */
        uint64_t n;
        if (read(t->efd, &n, sizeof n) < 0) {
            /* nothing to read after all: the caller checks and waits again */
        }
    }
}

void posix_ticker_stop(posix_ticker *t)
{
    if (t->fd < 0)
        return;
    atomic_store(&t->stop, 1);
    pthread_join(t->thread, NULL); /* the timer fires within a period: the read returns */
    close(t->fd);
    close(t->efd);
    t->fd = -1;
}
