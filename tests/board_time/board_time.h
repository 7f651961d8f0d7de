/* The board's timing on the host: a rig that runs the controller in one host thread charges each
 * call what it costs on the board's Cortex-M4F at 168 MHz, and lets the board's interrupts preempt
 * the controller's thread where that time runs out, as fw/runtime.h orders the contexts:
 *   step     (highest) preempts the control tick and the thread;
 *   control  preempts the thread; a control tick that comes due while one runs is pending (one
 *            pending bit, as the NVIC's) and runs after it; one due while another is pending is
 *            lost (counted);
 *   thread   the rest, and what it waits for (fw_config.await) is the next interrupt.
 *
 * What is charged, in board instructions (scripts/target_bench.sh's figures, one instruction a
 * cycle): every inverse kinematics solve (tse_ik_f), forward kinematics solve (tse_fk_f) and
 * piece enclosure (tse_ik_enclose_f) the firmware makes, through the linker's --wrap (the
 * executable links with BOARD_TIME_WRAP, board_time/CMakeLists.txt; a solve inside another is
 * part of the outer one's figure); a step tick; a control tick's own work beyond its solves; a
 * poll of the thread.  The solves are by far the largest part of any long work (a validation is
 * solves and enclosures); the rest of a frame's handling is charged as the poll's figure.
 *
 * One board timeline at a time (the wrapped solves find it through a static pointer). */
#ifndef BOARD_TIME_H
#define BOARD_TIME_H

#include <stdbool.h>
#include <stdint.h>

#define BT_HZ 168000000u

/* scripts/target_bench.sh, release flags, float (README, "The board"). */
#define BT_IK 1378u           /* ik_float_cold: a solve from home, the dearer of the two */
#define BT_FK 2597u           /* fk_float */
#define BT_ENCLOSE 3621u      /* enclose_float */
#define BT_STEP_TICK 137u     /* step_tick_6axes_max: the tick that starts a segment */
#define BT_CONTROL_BASE 2531u /* control_segment (3,709) less its solve (ik_float_warm, 1,178) */
#define BT_POLL 2000u         /* a poll's frames, decoding, answers: an estimate, no solve */

typedef enum { BT_THREAD, BT_CONTROL, BT_STEP } bt_context;

typedef struct {
    void (*step)(void *arg);    /* one step tick (the rig's fw_step_tick and plant) */
    void (*control)(void *arg); /* one control tick (the rig's fw_control_tick and checks) */
    /* NULL, or true when the step generator has nothing running or queued: it emits nothing until
     * the next control tick queues a segment, so the step ticks up to it are skipped (a rig that
     * must be fast, the fuzzer's). */
    bool (*step_idle)(void *arg);
    void *arg;
    uint64_t *clock_us;         /* the fake clock the firmware reads, kept at the board's time */
} bt_hooks;

typedef struct {
    bt_hooks h;
    uint64_t now;               /* board cycles since the start */
    uint64_t next_step, next_control;
    uint64_t control_due;       /* when the pending control tick came due */
    uint32_t step_period, control_period; /* cycles */
    bt_context ctx;
    bool control_pending;
    bool idle;                  /* the thread waits or idles: any interrupt may run */
    /* The arrangement the board had before its control tick got an interrupt of its own (issue
     * 23): the control tick runs only between the thread's works, never inside one.  Only to show
     * what the rig catches (tests/sim/test_board_timing.c). */
    bool control_in_thread;
    /* Figures: */
    uint64_t control_lost;      /* control ticks lost (one came due while another was pending) */
    uint64_t control_late_max;  /* the longest a control tick began behind its time, cycles */
    uint64_t thread_run_max;    /* the longest the thread ran between two waits or polls, cycles */
    uint64_t thread_run_start;
    uint64_t charged[3];        /* cycles charged in each context */
} board_time;

/* A timeline at cycle 0 with its interrupts at step_hz and control_hz (each dividing BT_HZ),
 * the first of each one period from now; it becomes the one the wrapped solves charge. */
void bt_init(board_time *b, uint32_t step_hz, uint32_t control_hz, const bt_hooks *hooks);
/* No timeline: the wrapped solves charge nothing (while a rig boots the controller: fw_init's
 * solves are before the board's time starts). */
void bt_stop(void);
/* b is the timeline the wrapped solves charge again, where it stood. */
void bt_resume(board_time *b);

/* Charges the current context n cycles and runs what comes due meanwhile and may preempt it. */
void bt_charge(uint32_t n);

/* The thread's work: fn(arg) charged BT_POLL and its solves, preempted as it goes. */
void bt_thread(board_time *b, void (*fn)(void *), void *arg);

/* The thread waits (WFI): time runs to the next interrupt, which runs.  fw_config.await. */
void bt_await(void *b);

/* The thread idles until cycle t (interrupts run as they come due). */
void bt_idle_until(board_time *b, uint64_t t);

#endif
