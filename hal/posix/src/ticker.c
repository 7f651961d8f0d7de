#define _GNU_SOURCE
#include "hal_posix/ticker.h"

#include <poll.h>
#include <signal.h>
#include <sys/eventfd.h>
#include <sys/timerfd.h>
#include <time.h>
#include <unistd.h>

uint64_t posix_ticker_now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
}

static void signal_fd(int fd)
{
    const uint64_t one = 1;
    if (write(fd, &one, sizeof one) < 0) {
        /* the counter is full: the reader has plenty to read */
    }
}

static void drain_fd(int fd)
{
    uint64_t n;
    if (read(fd, &n, sizeof n) < 0) {
        /* nothing to read after all (non-blocking) */
    }
}

/* Whether the bus holds a frame (cfg.bus_fd; unknown: as if it did). */
static bool bus_holds(const posix_ticker *t)
{
    struct pollfd p = {t->cfg.bus_fd, POLLIN, 0};
    return t->cfg.bus_fd < 0 || poll(&p, 1, 0) != 0;
}

/* What lets a late period begun at `began` run (ticker.h): the thread has taken every frame that
 * came before it. */
static bool thread_ready(posix_ticker *t, uint64_t began)
{
    return atomic_load(&t->caught_up_ns) >= began || atomic_load(&t->awaits) != t->awaits_seen ||
           (atomic_load(&t->thread_idle) && !bus_holds(t));
}

/* The controller's thread's CPU time (ns). */
static uint64_t thread_cpu_ns(const posix_ticker *t)
{
    struct timespec ts;
    if (clock_gettime(t->thread_clock, &ts) != 0)
        return UINT64_MAX; /* cannot tell: as if it had used its bound */
    return (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
}

/* Before a late period: wait, bounded, until the controller's thread has caught up with it. */
static void wait_for_thread(posix_ticker *t, uint64_t began)
{
    if (t->cfg.late_wait_us == 0)
        return;
    if (t->gave_up_ns) {
        if (atomic_load(&t->caught_up_ns) < t->gave_up_ns && atomic_load(&t->awaits) == t->gave_up_awaits)
            return; /* still busy since the last wait ran out: nothing caught up, nothing handed over */
        t->gave_up_ns = 0;
    }
    /* Stored before the looks below, and the thread stores what it did before it loads
     * tick_waiting: either a look here sees what the thread did or the thread sees the flag and
     * signals (sequentially consistent). */
    atomic_store(&t->tick_waiting, true);
    if (!thread_ready(t, began)) {
        ++t->late_waits;
        const uint64_t bound = (uint64_t)t->cfg.late_wait_us * 1000u;
        const uint64_t cpu0 = thread_cpu_ns(t);
        const uint64_t deadline = began + POSIX_TICKER_WALL_BOUNDS * bound;
        signal_fd(t->wake_fd);
        while (!thread_ready(t, began) && !atomic_load(&t->stop)) {
            const uint64_t now = posix_ticker_now_ns();
            const uint64_t cpu = thread_cpu_ns(t);
            if (now >= deadline || cpu == UINT64_MAX || cpu - cpu0 >= bound) {
                ++t->late_timeouts;
                t->gave_up_ns = now;
                t->gave_up_awaits = atomic_load(&t->awaits);
                break;
            }
            /* Woken by the thread, or every millisecond to read its CPU time again. */
            const uint64_t left = deadline - now < 1000000u ? deadline - now : 1000000u;
            const struct timespec ts = {0, (long)left};
            struct pollfd p = {t->caught_fd, POLLIN, 0};
            if (ppoll(&p, 1, &ts, NULL) > 0)
                drain_fd(t->caught_fd);
        }
    }
    atomic_store(&t->tick_waiting, false);
}

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
        /* Late periods are made up, so simulated time keeps pace with the wall clock. */
        for (uint64_t e = 0; e < expirations && !atomic_load(&t->stop); ++e) {
            const uint64_t due = t->start_ns + (t->periods + 1u) * t->period_ns;
            const uint64_t began = posix_ticker_now_ns();
            t->late = began >= due + t->period_ns;
            if (t->late)
                wait_for_thread(t, began);
            t->due_ns = due;
            t->began_ns = began;
            /* This call takes whatever the thread handed over before it: its waits so far are
             * answered. */
            t->awaits_seen = atomic_load(&t->awaits);
            t->cfg.control(t->cfg.arg);
            ++t->periods;
            signal_fd(t->efd);
            for (uint32_t s = 0; s < t->steps; ++s)
                t->cfg.step(t->cfg.arg);
        }
    }
    return NULL;
}

static int new_eventfd(void)
{
    return eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK);
}

int posix_ticker_start(posix_ticker *t, const posix_ticker_config *cfg)
{
    t->fd = t->efd = t->wake_fd = t->caught_fd = -1;
    if (cfg->control_hz == 0 || cfg->step_hz % cfg->control_hz != 0 || 1000000000u % cfg->control_hz != 0)
        return -1;
    t->cfg = *cfg;
    atomic_store(&t->stop, 0);
    t->periods = t->overruns = t->max_behind = t->late_waits = t->late_timeouts = 0;
    t->due_ns = t->began_ns = 0;
    t->late = false;
    atomic_store(&t->caught_up_ns, 0);
    atomic_store(&t->awaits, 0);
    atomic_store(&t->tick_waiting, false);
    atomic_store(&t->thread_idle, false);
    t->awaits_seen = 0;
    t->gave_up_ns = 0;
    t->steps = cfg->step_hz / cfg->control_hz;
    if (pthread_getcpuclockid(pthread_self(), &t->thread_clock) != 0)
        return -1;
    t->period_ns = 1000000000u / cfg->control_hz;
    t->efd = new_eventfd();
    t->wake_fd = new_eventfd();
    t->caught_fd = new_eventfd();
    t->fd = timerfd_create(CLOCK_MONOTONIC, TFD_CLOEXEC);
    int rc = t->efd >= 0 && t->wake_fd >= 0 && t->caught_fd >= 0 && t->fd >= 0 ? 0 : -1;
    if (rc == 0) {
        /* Absolute: period k is due at start + k periods, which the tick thread reckons with. */
        t->start_ns = posix_ticker_now_ns();
        const uint64_t first = t->start_ns + t->period_ns;
        const struct itimerspec its = {{0, (long)t->period_ns},
                                       {(time_t)(first / 1000000000u), (long)(first % 1000000000u)}};
        sigset_t all, old;
        sigfillset(&all);
        /* The thread inherits the mask: every signal stays with the caller's thread. */
        pthread_sigmask(SIG_SETMASK, &all, &old);
        rc = timerfd_settime(t->fd, TFD_TIMER_ABSTIME, &its, NULL) == 0 &&
                     pthread_create(&t->thread, NULL, tick_thread, t) == 0
                 ? 0
                 : -1;
        pthread_sigmask(SIG_SETMASK, &old, NULL);
    }
    if (rc != 0) {
        const int fds[] = {t->fd, t->efd, t->wake_fd, t->caught_fd};
        for (unsigned i = 0; i < 4; ++i)
            if (fds[i] >= 0)
                close(fds[i]);
        t->fd = -1;
    }
    return rc;
}

/* The thread did something a waiting late period waits for: tell it. */
static void thread_moved(posix_ticker *t)
{
    if (atomic_load(&t->tick_waiting))
        signal_fd(t->caught_fd);
}

void posix_ticker_await(posix_ticker *t)
{
    atomic_fetch_add(&t->awaits, 1u);
    thread_moved(t);
    struct pollfd p = {t->efd, POLLIN, 0};
    if (poll(&p, 1, 2) > 0) /* a control call comes every period: 2 ms is a margin, not a wait */
        drain_fd(t->efd);
}

void posix_ticker_caught_up(posix_ticker *t, uint64_t look_ns)
{
    if (look_ns > atomic_load(&t->caught_up_ns)) /* only this thread stores it */
        atomic_store(&t->caught_up_ns, look_ns);
    thread_moved(t);
}

void posix_ticker_thread_wait(posix_ticker *t, int bus_fd, int timeout_ms)
{
    struct pollfd p[2] = {{bus_fd, POLLIN, 0}, {t->wake_fd, POLLIN, 0}};
    atomic_store(&t->thread_idle, true);
    thread_moved(t);
    const int n = poll(p, 2, timeout_ms);
    atomic_store(&t->thread_idle, false);
    if (n > 0 && (p[1].revents & POLLIN))
        drain_fd(t->wake_fd);
}

void posix_ticker_stop(posix_ticker *t)
{
    if (t->fd < 0)
        return;
    atomic_store(&t->stop, 1);
    signal_fd(t->caught_fd); /* a late period waiting for the thread stops waiting */
    pthread_join(t->thread, NULL); /* the timer fires within a period */
    close(t->fd);
    close(t->efd);
    close(t->wake_fd);
    close(t->caught_fd);
    t->fd = -1;
}
