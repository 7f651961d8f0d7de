/* The control tick and the step interrupts in a thread of their own (fw/runtime.h: the control
 * context, and the step context inside it): every control period one control call, then the
 * period's step calls back to back.  The plant's clock is the step count, so simulated physics
 * stays exact whatever the scheduler does.  The thread blocks every signal: they go to the
 * controller's thread.
 *
 * Late periods.  A host that schedules the process late (a loaded machine, a VM) leaves the tick
 * periods behind; it makes them up back to back.  On a board the controller's thread takes the
 * frames that come between two control periods before the second; made up in a burst here, the
 * periods would consume the time the frames were meant for while the frames sit unread on the bus
 * (a streamed trajectory runs out of rows; the host paces itself by the controller's reports, so
 * what it sends belongs to the controller's time, however far that is behind the clock).  So a
 * late period - one run when the next is already due - first waits until the controller's thread
 * has taken every frame that came before the period began: it has looked at the bus since then
 * and found it empty (posix_ticker_caught_up), or it waits for the tick (posix_ticker_await: it
 * handed what it read over, and this period takes it), or it waits on a bus that holds nothing
 * (posix_ticker_thread_wait, and nothing to read on cfg.bus_fd).  The tick wakes the thread for
 * it (posix_ticker_thread_wait returns).  The wait is bounded by the CPU time the thread spends
 * meanwhile (late_wait_us): a thread busy for longer (a long validation, which on the board runs
 * while the tick keeps its periods) holds the tick once by the bound, and no late period waits
 * again until the thread has caught up or handed something over after that.  A thread the host does not schedule spends
 * nothing, so a loaded machine (or a VM the host stalls) does not end the wait: the tick waiting
 * leaves the thread the CPU.  A thread blocked elsewhere ends it after POSIX_TICKER_WALL_BOUNDS
 * bounds of wall time.  A period on time never waits, as the board's interrupt never does.
 *
 * The thread that starts the ticker is the controller's thread. */
#ifndef HAL_POSIX_TICKER_H
#define HAL_POSIX_TICKER_H

#include <pthread.h>
#include <stdatomic.h>
#include <stdbool.h>
#include <stdint.h>
#include <time.h>

/* A late period's wait ends after this many late_wait_us of wall time however little CPU time the
 * thread had. */
#define POSIX_TICKER_WALL_BOUNDS 20u

typedef struct {
    uint32_t control_hz, step_hz; /* step_hz a multiple of control_hz, control_hz dividing 1e9 */
    void (*control)(void *arg);
    void (*step)(void *arg);
    void *arg;
    uint32_t late_wait_us; /* the controller's thread's CPU time a late period waits for it at most;
                            * 0: it never waits */
    int bus_fd;            /* the bus the controller's thread reads (a late period looks whether it
                            * holds a frame); -1: unknown, as if it always did */
} posix_ticker_config;

typedef struct {
    /* The counts, final after posix_ticker_stop. */
    uint64_t periods;       /* control periods run */
    uint64_t overruns;      /* of them, periods the process was too late for (run late, back to back) */
    uint64_t max_behind;    /* the most periods it was ever behind at once */
    uint64_t late_waits;    /* late periods that waited for the controller's thread */
    uint64_t late_timeouts; /* of those, waits the bound ended */
    /* For the control callback: the period under way's due time and when it began, before any
     * wait (CLOCK_MONOTONIC, ns), and whether it was late (began when the next was due already). */
    uint64_t due_ns, began_ns;
    bool late;
    /* Shared with the controller's thread. */
    atomic_int stop;
    atomic_uint_least64_t caught_up_ns; /* the thread had taken everything the bus held before it */
    atomic_uint awaits;                 /* the thread's waits for the tick */
    atomic_bool thread_idle;            /* the thread waits on the bus, everything before taken */
    atomic_bool tick_waiting;           /* the tick waits for the thread to move */
    /* The tick thread's own. */
    posix_ticker_config cfg;
    pthread_t thread;
    clockid_t thread_clock; /* the controller's thread's CPU clock */
    int fd;        /* the timer */
    int efd;       /* signalled after every control call (posix_ticker_await) */
    int wake_fd;   /* signalled when a late period waits for the thread */
    int caught_fd; /* signalled when the thread catches up or waits while the tick waits */
    uint32_t steps;
    uint64_t start_ns, period_ns;
    unsigned awaits_seen;
    uint64_t gave_up_ns;      /* a wait ran out then (0: none): none until the thread moves after it */
    unsigned gave_up_awaits;  /* its awaits then */
} posix_ticker;

/* CLOCK_MONOTONIC in nanoseconds: the ticker's time. */
uint64_t posix_ticker_now_ns(void);

/* Starts the tick thread.  Returns 0, or -1 for rates it cannot keep or a thread or timer it
 * cannot have. */
int posix_ticker_start(posix_ticker *t, const posix_ticker_config *cfg);

/* Waits until the tick thread has made a control call since the wait began, or one that came
 * just before it (the caller checks what it waits for and waits again): for the controller's
 * thread handing a command over (fw_config.await).  Never makes the tick thread wait; a late
 * period waiting for the thread runs. */
void posix_ticker_await(posix_ticker *t);

/* From the controller's thread: it has taken every frame that came before look_ns (it looked at
 * that time or later and found the bus empty).  Late periods begun before then may run. */
void posix_ticker_caught_up(posix_ticker *t, uint64_t look_ns);

/* From the controller's thread between two looks at the bus: waits up to timeout_ms for a frame
 * on bus_fd, or for a late period asking the thread to catch up. */
void posix_ticker_thread_wait(posix_ticker *t, int bus_fd, int timeout_ms);

/* Stops the tick thread and waits for it; the counts are then final. */
void posix_ticker_stop(posix_ticker *t);

#endif
