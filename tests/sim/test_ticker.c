/* tse-sim's tick thread (hal_posix/ticker.h) against a controller's thread that is slow to take
 * its frames: a late control period runs only once the thread has taken every frame that came
 * before the period began, or handed it over; a thread that does neither holds the tick once, by
 * the bound (its CPU time) or the backstop (wall time).  The bus is a datagram socket pair fed a message a millisecond; the tick is made late
 * by control calls that sleep, as a host that does not schedule the process would. */
#define _GNU_SOURCE
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <errno.h>
#include <fcntl.h>
#include <string.h>
#include <pthread.h>
#include <stdatomic.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include "hal_posix/ticker.h"

#define HZ 1000u
#define MESSAGES 600u /* one a millisecond */

static void sleep_us(unsigned us)
{
    const struct timespec ts = {0, (long)us * 1000};
    while (nanosleep(&ts, NULL) != 0 && errno == EINTR) {
    }
}

typedef struct {
    int fd[2]; /* [0] the controller's end, [1] the host's */
    pthread_t producer;
    uint64_t sent_ns[MESSAGES]; /* when each send had returned: on the bus before then */
    atomic_uint sent;
    atomic_uint taken;   /* read by the thread (and, handing over, taken by the tick) */
    atomic_uint pending; /* handed over: message number + 1; 0 none */
    unsigned tick_took;  /* the last message number + 1 the tick took */
    /* the tick's */
    posix_ticker *t;
    unsigned stall_every, stall_us;
    atomic_uint calls;
    unsigned late, late_missing;
} bus;

static void *produce(void *arg)
{
    bus *b = arg;
    for (uint32_t i = 0; i < MESSAGES; ++i) {
        if (send(b->fd[1], &i, sizeof i, 0) != (ssize_t)sizeof i)
            break;
        b->sent_ns[i] = posix_ticker_now_ns();
        atomic_store(&b->sent, i + 1u);
        sleep_us(1000);
    }
    return NULL;
}

static void bus_open(bus *b)
{
    memset(b, 0, sizeof *b);
    assert_int_equal(socketpair(AF_UNIX, SOCK_DGRAM, 0, b->fd), 0);
    const int one = 1 << 20;
    setsockopt(b->fd[1], SOL_SOCKET, SO_SNDBUF, &one, sizeof one);
    setsockopt(b->fd[0], SOL_SOCKET, SO_RCVBUF, &one, sizeof one);
    fcntl(b->fd[0], F_SETFL, O_NONBLOCK);
}

static void bus_close(bus *b)
{
    close(b->fd[0]);
    close(b->fd[1]);
}

/* Messages whose send had returned before `when`. */
static unsigned sent_before(bus *b, uint64_t when)
{
    const unsigned n = atomic_load(&b->sent);
    unsigned k = 0;
    while (k < n && b->sent_ns[k] < when)
        ++k;
    return k;
}

/* The control call: takes what was handed over; in a late period, counts whether a message that
 * came before the period began is still not taken (what the thread reads without handing over
 * counts as taken); every stall_every calls sleeps stall_us, leaving the tick that much behind. */
static void control(void *arg)
{
    bus *b = arg;
    const unsigned p = atomic_load(&b->pending);
    if (p != b->tick_took) {
        b->tick_took = p;
        atomic_store(&b->taken, p);
    }
    if (b->t->late) {
        ++b->late;
        if (atomic_load(&b->taken) < sent_before(b, b->t->began_ns))
            ++b->late_missing;
    }
    if (b->stall_every && (atomic_fetch_add(&b->calls, 1u) + 1u) % b->stall_every == 0)
        sleep_us(b->stall_us);
}

static void step(void *arg)
{
    (void)arg;
}

static void start(bus *b, posix_ticker *t, uint32_t late_wait_us, int bus_fd)
{
    b->t = t;
    const posix_ticker_config cfg = {HZ, HZ, control, step, b, late_wait_us, bus_fd};
    assert_int_equal(posix_ticker_start(t, &cfg), 0);
    assert_int_equal(pthread_create(&b->producer, NULL, produce, b), 0);
}

/* The controller's thread, slow: every time it wakes it takes delay_us before it reads the bus;
 * handing over, it hands each message over and waits for the tick to take it.  Until every
 * message has been read. */
static void thread_run(bus *b, posix_ticker *t, unsigned delay_us, bool hand_over)
{
    unsigned read_count = 0;
    while (read_count < MESSAGES) {
        const uint64_t look = posix_ticker_now_ns();
        uint32_t m;
        while (recv(b->fd[0], &m, sizeof m, 0) == (ssize_t)sizeof m) {
            ++read_count;
            if (hand_over) {
                /* The tick takes it in its next period: two seconds is a margin no load reaches,
                 * and ends the test where the tick waits for this thread instead. */
                atomic_store(&b->pending, m + 1u);
                const uint64_t posted = posix_ticker_now_ns();
                while (atomic_load(&b->taken) != m + 1u && posix_ticker_now_ns() - posted < 2000000000u)
                    posix_ticker_await(t);
                if (atomic_load(&b->taken) != m + 1u)
                    fail_msg("message %u handed over was not taken within 2 s", (unsigned)m);
            } else {
                atomic_store(&b->taken, read_count);
            }
        }
        posix_ticker_caught_up(t, look);
        posix_ticker_thread_wait(t, b->fd[0], 5);
        sleep_us(delay_us);
    }
}

static void finish(bus *b, posix_ticker *t)
{
    pthread_join(b->producer, NULL);
    posix_ticker_stop(t);
    bus_close(b);
}

/* A message a millisecond to a thread that takes 3 ms to come to the bus each time it wakes (and,
 * handing over, hands each over), the tick stalled 30 ms every 100 periods; the bound (the
 * thread's CPU time) far beyond any wait here: it never ends one. */
static void run_streaming(bus *b, posix_ticker *t, uint32_t late_wait_us, bool hand_over)
{
    bus_open(b);
    b->stall_every = 100;
    b->stall_us = 30000;
    start(b, t, late_wait_us, b->fd[0]);
    thread_run(b, t, 3000, hand_over);
    finish(b, t);
}

/* Frames that came before a late period are read before it runs, however slow the thread. */
static void test_late_period_waits_for_the_frames_before_it(void **state)
{
    (void)state;
    static bus b;
    static posix_ticker t;
    run_streaming(&b, &t, 5000000u, false);
    print_message("%u late periods of %llu (%llu waited for the thread), %u with a message before them unread\n",
                  b.late, (unsigned long long)t.periods, (unsigned long long)t.late_waits, b.late_missing);
    assert_true(b.late >= 29u); /* the first stall alone leaves 29 periods late */
    assert_int_equal(b.late_missing, 0);
    assert_int_equal(t.late_timeouts, 0);
}

/* A thread waiting for the tick to take what it handed over is not waited for: one late period
 * takes it (the messages behind it may wait on the bus meanwhile), then the tick waits for the
 * thread again.  Were the thread waited for, every wait would run to the bound (the wall-time
 * backstop, 4 s: the thread waiting spends no CPU time). */
static void test_hand_over_lets_one_late_period_run(void **state)
{
    (void)state;
    static bus b;
    static posix_ticker t;
    run_streaming(&b, &t, 200000u, true);
    print_message("%u late periods (%llu waited for the thread, %llu to the bound)\n", b.late,
                  (unsigned long long)t.late_waits, (unsigned long long)t.late_timeouts);
    assert_true(b.late >= 29u);
    assert_int_equal(atomic_load(&b.taken), MESSAGES);
    assert_int_equal(t.late_timeouts, 0);
}

/* The tick stalls five times (every 50 periods for 10 ms) beside a controller's thread that never
 * looks at the bus: busy (spinning, as on a long validation) or blocked elsewhere (asleep). */
static void start_beside(bus *b, posix_ticker *t, uint32_t late_wait_us)
{
    memset(b, 0, sizeof *b);
    b->stall_every = 50;
    b->stall_us = 10000;
    b->t = t;
    const posix_ticker_config cfg = {HZ, HZ, control, step, b, late_wait_us, -1};
    assert_int_equal(posix_ticker_start(t, &cfg), 0);
}

static void run_beside(bus *b, posix_ticker *t, uint32_t late_wait_us, bool busy)
{
    start_beside(b, t, late_wait_us);
    while (atomic_load(&b->calls) < 5u * 50u + 1u)
        if (!busy)
            sleep_us(10000);
    posix_ticker_stop(t);
    print_message("%u late periods; %llu waited, %llu to the bound\n", b->late, (unsigned long long)t->late_waits,
                  (unsigned long long)t->late_timeouts);
    assert_true(b->late >= 5u * 5u); /* each stall leaves about 9 */
}

/* A thread busy for longer than the bound (CPU time) holds the tick once; later late periods do
 * not wait for it again until it has caught up. */
static void test_busy_thread_holds_the_tick_once(void **state)
{
    (void)state;
    static bus b;
    static posix_ticker t;
    const uint64_t t0 = posix_ticker_now_ns();
    run_beside(&b, &t, 20000u, true);
    assert_int_equal(t.late_waits, 1);
    assert_int_equal(t.late_timeouts, 1);
    /* Not the wall-time backstop (400 ms): the thread had the CPU. */
    assert_true(posix_ticker_now_ns() - t0 < POSIX_TICKER_WALL_BOUNDS * 20000000u);
}

/* A thread that hands something over after its busy stretch has moved: the next late period
 * waits for it again (and, the thread busy again, runs out again). */
static void test_hand_over_ends_a_busy_stretch(void **state)
{
    (void)state;
    static bus b;
    static posix_ticker t;
    start_beside(&b, &t, 20000u);
    while (__atomic_load_n(&t.late_timeouts, __ATOMIC_RELAXED) == 0) {
    }
    posix_ticker_await(&t); /* handed over, taken by the next call */
    const unsigned calls = atomic_load(&b.calls);
    while (atomic_load(&b.calls) < calls + 2u * 50u) {
    }
    posix_ticker_stop(&t);
    print_message("%llu waited, %llu to the bound\n", (unsigned long long)t.late_waits,
                  (unsigned long long)t.late_timeouts);
    assert_int_equal(t.late_waits, 2);
    assert_int_equal(t.late_timeouts, 2);
}

/* A thread blocked elsewhere spends no CPU time: the wall-time backstop ends the wait, once. */
static void test_blocked_thread_holds_the_tick_by_the_backstop(void **state)
{
    (void)state;
    static bus b;
    static posix_ticker t;
    const uint64_t t0 = posix_ticker_now_ns();
    run_beside(&b, &t, 5000u, false);
    assert_int_equal(t.late_waits, 1);
    assert_int_equal(t.late_timeouts, 1);
    /* Five stalls of 10 ms and 250 periods, and the backstop's 100 ms: at least the backstop. */
    assert_true(posix_ticker_now_ns() - t0 >= POSIX_TICKER_WALL_BOUNDS * 5000000u);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_late_period_waits_for_the_frames_before_it),
        cmocka_unit_test(test_hand_over_lets_one_late_period_run),
        cmocka_unit_test(test_busy_thread_holds_the_tick_once),
        cmocka_unit_test(test_hand_over_ends_a_busy_stretch),
        cmocka_unit_test(test_blocked_thread_holds_the_tick_by_the_backstop),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
