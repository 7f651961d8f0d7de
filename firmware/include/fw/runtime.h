/* How the controller runs: its contexts, what each does, and in which order.  The one place that
 * says it; the board, the simulator, the test rigs, the fuzzer and the benchmarks all run the
 * controller through these calls.
 *
 * Contexts, most urgent first (each preempts those below it, never the reverse):
 *   step     fw_step_tick, step_hz: the step generator onto the STEP and DIR outputs.
 *            Board: TIM2's interrupt, priority 0.
 *   e-stop   fw_estop_isr: stepping halts and the drives go off at once.  Board: EXTI, priority 0
 *            (the step interrupt's level: neither preempts the other).
 *   control  fw_control_tick, segment_hz: the e-stop completed, what the thread handed over
 *            taken, supervision (inputs, the host's silence as the thread last read the bus,
 *            bus, overruns), the motion source advanced and
 *            the next setpoints queued for the step generator, the state published.  It never
 *            waits for the thread.  Board: TIM3's interrupt, priority 2 (below the step
 *            interrupt and its pulse timer, above CAN); simulator: its tick thread.
 *   thread   fw_poll: frames in (commands decoded, authorised, planned and validated), frames out
 *            (answers, STATUS, telemetry, how a trajectory ended).  Board: the main loop, after
 *            every interrupt; simulator: its main thread.
 *
 * The hand-over (firmware/src/handover.h): the thread never writes what the tick owns (state,
 * faults, drives, motion, the trajectory queue, the step generator, its copy of the parameters);
 * it hands each command that changes them to the tick, one at a time, and waits for the tick's
 * verdict before answering (fw_config.await).  The tick publishes its state for the thread
 * after every call; the thread reads a consistent copy (a sequence counter, retried if the tick
 * wrote meanwhile).  Nothing the tick reads is guarded by a lock.  A long validation (a move, a
 * blend, a trajectory row) runs in the thread in pieces (fw/work.h): between two pieces the
 * thread takes heartbeats, sends its STATUS and telemetry when due, and a STOP or an e-stop frame
 * ends the validation at once when the robot moves; other commands wait their turn in the
 * thread's inbox and are answered in order.
 *
 * On a platform with one context (fw_config.await NULL), fw_run_period is a control period in
 * the order the board's interrupts give it: the thread's work on what arrived before the period
 * (a hand-over taken in place), the control tick, then the period's step ticks. */
#ifndef FW_RUNTIME_H
#define FW_RUNTIME_H

#include <stdint.h>

#include "fw/controller.h"

/* The step interrupt: one tick of the step generator onto the outputs. */
void fw_step_tick(fw_controller *c);

/* The control tick (see above). */
void fw_control_tick(fw_controller *c);

/* The thread's work: every frame waiting, and the periodic frames due. */
void fw_poll(fw_controller *c);

/* The emergency stop from an interrupt (the e-stop input's EXTI), of any priority.  At once: the
 * step generator halts (no step from its next tick on; a step tick this interrupt preempted
 * completes) and the drives are switched off; then it leaves a request that the next control
 * tick completes first thing (state ESTOP, latched until CLEAR_FAULT, the zero dropped).  Between
 * the two nothing emits a step, and an ENABLE taken meanwhile does not switch the drives back on. */
void fw_estop_isr(fw_controller *c);

/* Counts the thread's progress: every poll, and every piece of a long validation.  A watchdog fed
 * from the control tick while this moves is fed by what proves both contexts alive. */
uint32_t fw_thread_progress(const fw_controller *c);

/* What fw_run_period just did, for a platform that charges it time or looks after it. */
typedef enum {
    FW_RAN_POLL,    /* the thread's work */
    FW_RAN_CONTROL, /* a control tick */
    FW_RAN_STEP     /* a step tick */
} fw_ran;

/* Called after each call of a period (NULL: nothing).  A rig's plant takes its step after each
 * FW_RAN_STEP; a rig that charges each call its cost on the board does it here. */
typedef void (*fw_ran_hook)(void *ctx, fw_ran what);

/* One control period where one context runs everything (fw_config.await NULL): fw_period_start,
 * then the period's step_hz / segment_hz step ticks. */
void fw_run_period(fw_controller *c, fw_ran_hook hook, void *ctx);

/* The start of a control period: the thread's work, then the control tick.  A rig that runs the
 * step ticks itself (the fuzzer skips those of a generator at rest) starts each period with it. */
void fw_period_start(fw_controller *c, fw_ran_hook hook, void *ctx);

#endif
