/* How the controller runs (fw/runtime.h): long work in pieces that look at the bus (fw/work.h), a
 * STOP that ends a validation under way, and the two contexts of the board - the control tick in a
 * thread of its own, at once with the controller's thread that plans and validates - handing
 * commands over without a lock, and taking the host's heartbeats while it waits for the tick. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <pthread.h>
#include <sched.h>
#include <time.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stdatomic.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "fw/work.h"
#include "harness.h"
#include "tse/ik.h"

/* ---- fw/work.h ---- */

static unsigned looks, stop_after;

static bool watcher(void *ctx)
{
    assert_ptr_equal(ctx, &looks);
    return ++looks >= stop_after;
}

/* Nobody watching: a point never stops the walk.  Watched: a look every FW_WORK_STRIDE points,
 * and the walk stops at the look that says so. */
static void test_work_looks_every_stride(void **state)
{
    (void)state;
    for (unsigned i = 0; i < 3 * FW_WORK_STRIDE; ++i)
        assert_false(fw_work_point());
    looks = 0;
    stop_after = 3;
    fw_work_begin(watcher, &looks);
    unsigned points = 0;
    while (!fw_work_point())
        ++points;
    ++points; /* the one that said stop */
    assert_int_equal(looks, 3);
    assert_int_equal(points, 3 * FW_WORK_STRIDE);
    fw_work_end();
    for (unsigned i = 0; i < 3 * FW_WORK_STRIDE; ++i)
        assert_false(fw_work_point());
    assert_int_equal(looks, 3);
}

/* ---- a STOP during a validation ---- */

static unsigned index_of(unsigned from, uint8_t kind, proto_msg m)
{
    for (unsigned i = from; i < F.tx_count; ++i)
        if ((F.tx[i].id >> 4) == kind && F.tx[i].data[0] == proto_table[m].function)
            return i;
    fail_msg("no answer of kind 0x%02x to %s", kind, proto_table[m].name);
    return 0;
}

/* Half a second into a 3 s move to blend_first from idle: where a commit to blend_second is
 * a blend, validated over the whole of both moves, thousands of segments. */
static const double blend_first[6] = {0.06, 0.0, 1.05, 0, 0, 0}, blend_second[6] = {-0.06, 0.06, 1.15, 0, 0, 0.1};

static void moving_to_first(void)
{
    reach(FW_STATE_IDLE);
    move_to(blend_first, 3000);
    run(500);
    assert_int_equal(fw_state_of(C), FW_STATE_MOVING);
}

/* A blend is validated over the whole of both moves, thousands of segments; a STOP that arrives
 * behind its commit is seen during the validation: answered first, the robot brought to rest,
 * and the commit it cut short refused as out of state (it met a stopping robot).  Nothing of it
 * runs: the robot rests short of the first target and far from the second. */
static void test_stop_ends_a_validation(void **state)
{
    (void)state;
    moving_to_first();
    const unsigned from = F.tx_count;
    move_to(blend_second, 3000);
    cmd(PM_STOP);
    fw_poll(C);
    const unsigned stop_ack = index_of(from, proto_table[PM_ACK].function, PM_STOP);
    const unsigned commit_reject = index_of(from, proto_table[PM_REJECT].function, PM_MOVE_COMMIT);
    assert_true(stop_ack < commit_reject);
    assert_int_equal(F.tx[commit_reject].data[2], FW_REASON_STATE);
    assert_int_equal(answer(from, proto_table[PM_MOVE_COMMIT].function, NULL), 'r');
    assert_int_equal(fw_state_of(C), FW_STATE_STOPPING);
    assert_false(now().has_next);
    for (int i = 0; i < 300 && fw_state_of(C) != FW_STATE_IDLE; ++i)
        run(10);
    assert_int_equal(fw_state_of(C), FW_STATE_IDLE);
    tse_ik_result r1, r2;
    assert_int_equal(tse_ik(fw_geometry_of(C), blend_first, NULL, &r1), TSE_OK);
    assert_int_equal(tse_ik(fw_geometry_of(C), blend_second, NULL, &r2), TSE_OK);
    bool short_of_first = false;
    for (int k = 0; k < 6; ++k) {
        short_of_first |= labs(F.steps[k] - lround(r1.q[k] * 1280000.0)) > 100;
        assert_true(labs(F.steps[k] - lround(r2.q[k] * 1280000.0)) > 100 ||
                    fabs(r1.q[k] - r2.q[k]) < 1e-4);
    }
    assert_true(short_of_first);
}

/* ---- the host goes on hearing the controller during a validation ---- */

static unsigned bus_reads;

/* Time passes as the thread works: 0.5 ms at every read of the bus (a look comes every few
 * pieces, fw/work.h), so the blend's validation below lasts hundreds of milliseconds. */
static void time_passes_at_reads(void *arg, fake_hook_point at)
{
    if (at == FAKE_AT_RECEIVE) {
        ((fake_hal *)arg)->now_us += 500u;
        ++bus_reads;
    }
}

static unsigned count_of(unsigned from, unsigned to, proto_msg m)
{
    unsigned n = 0;
    for (unsigned i = from; i < to; ++i)
        n += (F.tx[i].id >> PROTO_NODE_BITS) == proto_table[m].function;
    return n;
}

/* A validation that takes long (a blend, over both moves segment by segment) does not silence
 * the controller: STATUS and telemetry go out at their periods while it runs, each STATUS with
 * the state the tick is in (moving) and the last commit answered (the one running), each
 * telemetry period whole (SLIDES A to C, then FK A to C).  Before, nothing went out until the
 * answer: on the board, 130 ms for such a blend and 110 ms for the costliest commit found. */
static void test_status_and_telemetry_during_a_validation(void **state)
{
    (void)state;
    moving_to_first();
    const uint8_t running = (uint8_t)(seq - 1u);
    move_to(blend_second, 3000);
    const unsigned from = F.tx_count;
    bus_reads = 0;
    const uint64_t t0 = F.now_us;
    F.hook = time_passes_at_reads;
    F.hook_arg = &F;
    fw_poll(C);
    F.hook = NULL;
    const uint64_t took_us = F.now_us - t0;
    const unsigned ans = index_of(from, proto_table[PM_ACK].function, PM_MOVE_COMMIT);
    print_message("validation: %u reads of the bus, %.0f ms\n", bus_reads, (double)took_us / 1000.0);
    assert_true(took_us >= 300000u); /* long enough to need several periods of each */
    /* Due every 100 ms (status_ms) and 50 ms (telemetry_ms), from the poll's start. */
    const unsigned statuses = count_of(from, ans, PM_STATUS);
    assert_true(statuses >= (unsigned)(took_us / 100000u));
    assert_true(count_of(from, ans, PM_SLIDES_A) >= (unsigned)(took_us / 50000u));
    assert_int_equal(count_of(from, ans, PM_FK_C), count_of(from, ans, PM_SLIDES_A));
    for (unsigned i = from; i < ans; ++i) {
        const uint8_t fn = (uint8_t)(F.tx[i].id >> PROTO_NODE_BITS);
        if (fn == proto_table[PM_STATUS].function) {
            proto_message m;
            assert_int_equal(proto_decode(&F.tx[i], PROTO_TO_HOST, &m).reason, FW_REASON_NONE);
            assert_int_equal(m.v[0], FW_STATE_MOVING);
            assert_int_equal(m.v[5], running);
        } else if (fn == proto_table[PM_SLIDES_A].function) {
            assert_true(i + 5u < ans);
            for (unsigned k = 1; k < 6; ++k)
                assert_int_equal(F.tx[i + k].id >> PROTO_NODE_BITS,
                                 proto_table[k < 3 ? PM_SLIDES_A + k : PM_FK_A + (k - 3u)].function);
        }
    }
}

/* ---- two contexts ---- */

static _Atomic uint64_t clock_us; /* written by the tick thread, read by both */
static atomic_bool tick_stop;

static uint64_t now_us(void *ctx)
{
    (void)ctx;
    return atomic_load(&clock_us);
}

static void *tick_thread(void *arg)
{
    fw_controller *c = arg;
    const uint32_t steps = fw_config_of(c)->step_hz / fw_config_of(c)->segment_hz;
    while (!atomic_load(&tick_stop)) {
        fw_control_tick(c);
        for (uint32_t s = 0; s < steps; ++s)
            fw_step_tick(c);
        atomic_fetch_add(&clock_us, 1000000u / fw_config_of(c)->segment_hz);
        sched_yield();
    }
    return NULL;
}

static void await_yield(void *ctx)
{
    (void)ctx;
    sched_yield();
}

/* The controller's thread: polls (with a heartbeat each time) until the controller answered
 * `m` since tx index `from`; returns the answer ('a', 'r'). */
static char poll_until_answer(unsigned from, proto_msg m)
{
    for (;;) {
        assert_true(F.tx_count < FAKE_QUEUE);
        heartbeat();
        fw_poll(C);
        const char a = answer(from, proto_table[m].function, NULL);
        if (a)
            return a;
        sched_yield();
    }
}

/* The newest STATUS's state since `from`, or -1. */
static int status_state(unsigned from)
{
    const hal_can_frame *f = fake_last(&F, proto_table[PM_STATUS].function, from);
    return f ? f->data[0] : -1;
}

/* The board's arrangement on the host: the control tick and the step ticks in a thread of their
 * own, as fast as it goes; this thread takes the frames and plans.  An ENABLE, a move, and a move
 * committed during it are handed over (fw_config.await) and answered with the tick's verdict; the
 * second joins the first (blended, or after it where the tick had already passed the blend), and
 * the robot ends on the second target to the step. */
static void test_tick_in_a_thread_of_its_own(void **state)
{
    (void)state;
    static fw_controller_mem mem;
    fw_hal hal;
    fake_hal_init(&F, &hal);
    hal.clock = (hal_clock){NULL, now_us};
    atomic_store(&clock_us, 0);
    const fw_config cfg = {1, 1000, 100000, await_yield, NULL, NULL};
    C = fw_init(&mem, &hal, &cfg);
    assert_non_null(C);
    assert_int_equal(fw_testing_homed_at_home(C), 0);
    seq = 1;
    atomic_store(&tick_stop, false);
    pthread_t th;
    assert_int_equal(pthread_create(&th, NULL, tick_thread, C), 0);

    /* The tick runs as fast as it goes: a second of this thread's absence on a loaded machine is
     * many of its seconds.  No watchdog, then. */
    assert_int_equal(set_param(FP_WATCHDOG_MS, 0, NULL, NULL), 'a');
    unsigned from = F.tx_count;
    cmd(PM_ENABLE);
    assert_int_equal(poll_until_answer(from, PM_ENABLE), 'a');
    const double first[6] = {0.06, 0.0, 1.05, 0, 0, 0}, second[6] = {0.06, 0.06, 1.10, 0, 0, 0.05};
    from = F.tx_count;
    move_to(first, 1500);
    assert_int_equal(poll_until_answer(from, PM_MOVE_COMMIT), 'a');
    from = F.tx_count;
    move_to(second, 1500);
    assert_int_equal(poll_until_answer(from, PM_MOVE_COMMIT), 'a');
    const hal_can_frame *info = fake_last(&F, proto_table[PM_MOVE_INFO].function, from);
    assert_non_null(info);
    assert_true(info->data[1] == FW_START_BLENDED || info->data[1] == FW_START_AFTER);
    /* Until a STATUS says idle: the tick runs on whatever this thread does (the moves take 3 s of
     * its time at most; a minute of the machine's is a bound no load reaches). */
    from = F.tx_count;
    struct timespec t0, t;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    while (status_state(from) != FW_STATE_IDLE) {
        if (F.tx_count > FAKE_QUEUE / 2) /* this thread sends: it may empty the bus */
            F.tx_count = from = 0;
        heartbeat();
        fw_poll(C);
        sched_yield();
        clock_gettime(CLOCK_MONOTONIC, &t);
        assert_true(t.tv_sec - t0.tv_sec < 60);
    }
    atomic_store(&tick_stop, true);
    assert_int_equal(pthread_join(th, NULL), 0);
    assert_int_equal(fw_state_of(C), FW_STATE_IDLE);
    tse_ik_result r;
    assert_int_equal(tse_ik(fw_geometry_of(C), second, NULL, &r), TSE_OK);
    int32_t pos[6];
    stepgen_positions(fw_stepgen_of(C), pos);
    for (int k = 0; k < 6; ++k)
        assert_int_equal(pos[k], lround(r.q[k] * 1280000.0));
}

/* ---- heartbeats while the thread waits ---- */

static int slow_calls; /* > 0: the tick takes the command on this many-th wait, 100 ms apart */

/* The thread's wait (fw_config.await), the tick played in place: at once, or late (slow_calls)
 * with the host's heartbeat arriving every 100 ms meanwhile. */
static void await_in_place(void *ctx)
{
    (void)ctx;
    if (slow_calls > 0) {
        F.now_us += 100000u;
        heartbeat();
        if (--slow_calls > 0)
            return;
    }
    fw_control_tick(C);
}

/* A control tick that takes a command 700 ms after it was handed over (the tick far behind, as
 * tse-sim's can be on a loaded machine): the heartbeats that came meanwhile were taken while the
 * thread waited, so the watchdog (500 ms) does not fire. */
static void test_heartbeats_taken_while_waiting(void **state)
{
    (void)state;
    static fw_controller_mem mem;
    fw_hal hal;
    fake_hal_init(&F, &hal);
    const fw_config cfg = {1, 1000, 100000, await_in_place, NULL, NULL};
    C = fw_init(&mem, &hal, &cfg);
    assert_non_null(C);
    assert_int_equal(fw_testing_homed_at_home(C), 0);
    seq = 1;
    slow_calls = 0;
    unsigned from = F.tx_count;
    cmd(PM_ENABLE);
    fw_poll(C);
    assert_int_equal(answer(from, proto_table[PM_ENABLE].function, NULL), 'a');
    assert_true(fw_drives_of(C));
    slow_calls = 7;
    from = F.tx_count;
    cmd(PM_STOP);
    fw_poll(C);
    assert_int_equal(slow_calls, 0);
    assert_int_equal(answer(from, proto_table[PM_STOP].function, NULL), 'a');
    assert_int_equal(fw_fault_of(C), FW_FAULT_NONE);
    assert_int_equal(fw_state_of(C), FW_STATE_IDLE);
}

/* Control periods with only the tick running (the thread not scheduled), the host's heartbeat
 * arriving on the bus every 10 ms: what tse-sim's tick thread does on a starved host, making up
 * late periods before its main thread runs. */
static void ticks_alone(uint32_t ms, bool host_alive)
{
    for (uint32_t t = 0; t < ms; ++t) {
        if (host_alive && t % 10u == 0)
            heartbeat();
        fake_tick_alone(&F, C);
    }
}

/* The watchdog calls the host silent only from what the thread read of the bus: a second of ticks
 * while heartbeats wait unread on the bus is no silence (the watchdog judged by the tick's clock
 * faulted here after 500 ms); once the thread reads them, the host is alive all along.  A host
 * really silent still faults, once the thread has found the bus empty for watchdog_ms. */
static void test_watchdog_judges_what_the_thread_read(void **state)
{
    (void)state;
    reach(FW_STATE_IDLE);
    assert_true(fw_drives_of(C));
    const uint32_t wd = (uint32_t)fw_params_of(C)->v[FP_WATCHDOG_MS];
    assert_true(wd > 0 && wd < 1000);
    ticks_alone(2 * wd, true);
    assert_int_equal(fw_fault_of(C), FW_FAULT_NONE);
    run(100); /* the thread runs again: every heartbeat waiting is taken */
    assert_int_equal(fw_fault_of(C), FW_FAULT_NONE);
    assert_int_equal(fw_state_of(C), FW_STATE_IDLE);
    /* The host falls silent: the thread goes on finding the bus empty. */
    fake_run(&F, C, wd - 20);
    assert_int_equal(fw_fault_of(C), FW_FAULT_NONE);
    fake_run(&F, C, 40);
    assert_int_equal(fw_fault_of(C), FW_FAULT_WATCHDOG);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_work_looks_every_stride),
        cmocka_unit_test(test_stop_ends_a_validation),
        cmocka_unit_test(test_status_and_telemetry_during_a_validation),
        cmocka_unit_test(test_tick_in_a_thread_of_its_own),
        cmocka_unit_test(test_heartbeats_taken_while_waiting),
        cmocka_unit_test(test_watchdog_judges_what_the_thread_read),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
