/* Step generator: interpolates each of the six slides between control-segment setpoints at the
 * step interrupt rate, in integer arithmetic (Bresenham), and nothing else.
 *
 * Promises:
 * - Exactness: when a segment ends, every axis has emitted exactly target - start steps, as long
 *   as the segment asks for no more than its capacity (see stepgen_capacity).  A segment that
 *   asks for more is counted as an overrun; it emits at the maximum rate, and what is left over is
 *   folded into the next segment, so the emitted count still converges to the setpoint.
 * - Direction set-up: after an axis changes direction it emits no step for dir_setup_ticks.
 * - Pulse spacing: two steps of one axis are at least min_step_interval ticks apart, which bounds
 *   the step rate per axis at isr_hz / min_step_interval and leaves room for the pulse width.
 * - Segments are double-buffered: the control loop queues the next setpoint while the current one
 *   runs, and the interrupt switches without a gap.  One producer (control loop) and one consumer
 *   (step interrupt) may run concurrently.
 * - Halt: stepgen_halt, callable from any context (an e-stop interrupt), stops stepping from the
 *   next tick on: a halted stepgen_tick emits no step and changes nothing.  stepgen_abort ends
 *   the halt (see there); nothing else does, and setpoints pushed meanwhile only wait.
 *
 * The interrupt's tick is short: per axis an add, a sign test and on a step a subtraction, no
 * division, nothing 64-bit; the first and last ticks of a segment and the end of a direction
 * set-up do a little more.  stepgen_push prepares each
 * segment (its deltas, directions, set-up delays and capacity clip) from where the segments
 * before it leave the axes, and the interrupt runs it where it was prepared, so that starting one
 * costs a few stores; the positions are not counted step by step but computed by
 * stepgen_positions from the running segment and its tick.
 *
 * No floating point, no heap; every operation is O(axes). */
#ifndef FW_STEPGEN_H
#define FW_STEPGEN_H

#include <stdatomic.h>
#include <stdbool.h>
#include <stdint.h>

#define STEPGEN_AXES 6
#define STEPGEN_QUEUE 4 /* setpoints that may wait behind the running segment (power of two) */

typedef struct {
    uint32_t ticks_per_segment; /* step interrupts per control segment, e.g. 200 kHz / 1 kHz */
    uint32_t dir_setup_ticks;   /* quiet ticks after a direction change (>= 1) */
    uint32_t min_step_interval; /* ticks between two steps of one axis (>= 1) */
} stepgen_config;

/* The interrupt's state of one axis: Bresenham as an error term, acc of the classic form (span at
 * the start of the axis' span ticks, + 2 delta a tick, a step and - 2 span when it reaches 2 span)
 * minus 2 span, so that the test is a sign. */
typedef struct {
    int32_t err;  /* < 0 between steps; the tick that brings it to >= 0 steps and takes dec off */
    uint32_t inc; /* added every tick: 2 delta, or 0 while a direction set-up holds the axis */
    uint32_t dec; /* 2 span */
} stepgen_axis;

#define STEPGEN_RING 8 /* slots: the running segment and up to STEPGEN_QUEUE waiting ones */

/* A segment as stepgen_push prepares it; while it runs, its axes are the interrupt's state.  The
 * ring has room for the running segment besides the waiting ones, so that the producer never
 * writes the running slot: the positions are computed from it. */
typedef struct {
    stepgen_axis ax[STEPGEN_AXES]; /* the interrupt's state (err = -span at the start) */
    int32_t start[STEPGEN_AXES];   /* positions when the segment begins */
    uint32_t delta[STEPGEN_AXES];  /* |steps| of each axis, within the segment's capacity */
    uint32_t event;                /* the first tick after which the interrupt must look again */
    uint8_t forward_mask;          /* bit i: axis i moves forward (an axis at rest keeps its pin) */
    uint8_t held_mask;             /* axes that change direction: quiet for dir_setup_ticks */
    bool overrun;                  /* it asked more than its capacity (counted when it starts) */
} stepgen_segment;

typedef struct {
    stepgen_config cfg;
    /* The interrupt's: the running (or last) segment. */
    uint32_t cur;      /* its slot in ring */
    uint32_t tick;     /* ticks elapsed in it */
    uint32_t event;    /* the end of the direction set-up, then the segment's last tick */
    bool running;
    uint8_t forward_mask;
    atomic_uint seq;   /* odd while the interrupt switches segments (see stepgen_positions) */
    /* Single-producer single-consumer ring of prepared segments. */
    stepgen_segment ring[STEPGEN_RING];
    atomic_uint head; /* written by the producer */
    atomic_uint tail; /* written by the consumer: segments started */
    atomic_bool halted; /* set by stepgen_halt, cleared by stepgen_abort */
    /* The producer's: where the queued segments leave the axes, which they reach exactly. */
    int32_t planned[STEPGEN_AXES];
    uint8_t planned_forward;
    uint32_t overruns;  /* segments that asked more than their capacity */
    uint32_t underruns; /* segment ends with nothing queued while not at rest */
} stepgen;

typedef struct {
    uint8_t step_mask;    /* axes to pulse on this tick */
    uint8_t forward_mask; /* direction of every axis, valid on every tick */
    bool dir_changed;     /* forward_mask differs from the previous tick's */
} stepgen_output;

/* Returns 0, or -1 for a configuration that cannot work (zero ticks, intervals, or a set-up time
 * that leaves no room for a step in a segment). */
int stepgen_init(stepgen *sg, const stepgen_config *cfg, const int32_t position[STEPGEN_AXES]);

/* Most steps one axis can emit in a segment; with a direction change the set-up time is taken
 * off.  The planner keeps every segment within this. */
uint32_t stepgen_capacity(const stepgen_config *cfg, bool direction_change);

/* Producer side: queue the setpoint (absolute, in steps) that the next segment ends at.
 * Returns 0, or -1 when the queue is full (nothing is queued). */
int stepgen_push(stepgen *sg, const int32_t target[STEPGEN_AXES]);

/* Setpoints queued and not yet started. */
unsigned stepgen_queued(const stepgen *sg);

/* Consumer side, once per step interrupt. */
stepgen_output stepgen_tick(stepgen *sg);

/* True when no segment runs and none is queued. */
bool stepgen_idle(const stepgen *sg);

/* Emergency stop, first half: no step from the next tick on.  Safe from any interrupt or thread;
 * a tick it interrupts (when called from a higher priority than the step interrupt) completes. */
void stepgen_halt(stepgen *sg);

/* Emergency stop, second half: abandons the running segment and every queued one, then ends the
 * halt.  The positions keep the steps actually emitted.  Call from the producer's context (or
 * with the step interrupt masked): it halts first itself, so that a step interrupt meanwhile
 * finds nothing to do. */
void stepgen_abort(stepgen *sg);

/* Position bookkeeping (homing sets the zero).  Only while idle; returns -1 otherwise.  From the
 * producer's context. */
int stepgen_set_position(stepgen *sg, const int32_t position[STEPGEN_AXES]);

/* Steps emitted so far, exactly, while the interrupt runs.  From the producer's context (or any
 * context the step interrupt may preempt but not the reverse). */
void stepgen_positions(const stepgen *sg, int32_t out[STEPGEN_AXES]);

#endif
