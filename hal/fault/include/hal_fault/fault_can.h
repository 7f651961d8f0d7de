/* A hal_can between a controller and its bus that injects faults into what the controller
 * receives, and can make it bus-off.
 *
 * Each frame taken from the bus suffers at most one fault, drawn with the configured
 * probabilities from a seeded generator (the same seed and traffic give the same faults):
 *   drop     the frame is lost;
 *   dup      it is handed over twice, the copy right after it;
 *   reorder  it is held until a later frame has been handed over (or delay_us at most);
 *   delay    it is held for delay_us;
 *   corrupt  one bit of its payload, its length, or one bit of its identifier changes.
 * Besides, within a silence window every frame from the bus is lost (the host has gone quiet),
 * and within a bus-off window the controller is bus-off: state() says so (and counts one bus-off
 * event per window, even one that ended between two looks), nothing is received (frames arriving
 * are lost) and every send is refused.  What the controller sends otherwise passes unchanged.
 *
 * A frame "reaches the controller" when receive() hands it over: a dropped frame never does, a
 * duplicated one does twice, a corrupted one does as its corrupted bytes.  The counts in
 * fault_can_stats add up:
 *   received + faults[dup] = delivered + faults[drop] + silenced + bus_off_lost + held. */
#ifndef HAL_FAULT_CAN_H
#define HAL_FAULT_CAN_H

#include <stdbool.h>
#include <stdint.h>

#include "hal/can.h"
#include "hal/clock.h"
#include "hal_fault/fault_rng.h"
#include "hal_fault/fault_time.h"

typedef enum { FAULT_DROP, FAULT_DUP, FAULT_REORDER, FAULT_DELAY, FAULT_CORRUPT, FAULT_CAN_KINDS } fault_can_kind;

/* What a corruption changes (FAULT_CORRUPT_ANY: one of the three at random, the payload half the
 * time). */
typedef enum { FAULT_CORRUPT_ANY, FAULT_CORRUPT_PAYLOAD, FAULT_CORRUPT_LENGTH, FAULT_CORRUPT_ID } fault_corrupt_how;

/* What the tap sees: a frame handed to the controller, or one the controller sent (before the
 * layer refuses it for a bus-off). */
typedef enum { FAULT_TAP_DELIVERED, FAULT_TAP_SENT } fault_can_tap;

typedef struct {
    uint64_t seed;
    double p[FAULT_CAN_KINDS]; /* probability per frame of each fault; their sum at most 1 */
    uint32_t delay_us;         /* how long delay holds a frame, and reorder at most */
    fault_corrupt_how corrupt_how;
    fault_window silence;
    fault_window bus_off;
    /* Corruptions not to make (NULL: none): asked with the frame and what the corruption drawn
     * would make of it; true leaves the frame whole (stats.spared). */
    bool (*spare)(void *arg, const hal_can_frame *before, const hal_can_frame *after);
    void *spare_arg;
    /* Sees every frame handed over and every frame sent (NULL: nothing). */
    void (*tap)(void *arg, fault_can_tap what, const hal_can_frame *f);
    void *tap_arg;
} fault_can_config;

typedef struct {
    uint32_t received;        /* frames taken from the bus */
    uint32_t delivered;       /* frames handed to the controller (a duplicate counts twice) */
    uint32_t faults[FAULT_CAN_KINDS];
    uint32_t corrupt_payload, corrupt_length, corrupt_id;
    uint32_t spared;          /* corruptions drawn but not made (config.spare) */
    uint32_t silenced;        /* frames lost to a silence window */
    uint32_t bus_off_lost;    /* frames lost while bus-off */
    uint32_t sent;            /* frames the controller sent */
    uint32_t send_refused;    /* of them, refused while bus-off */
    uint32_t bus_off_events;  /* bus-off windows begun */
} fault_can_stats;

#define FAULT_CAN_HOLD 32

typedef struct {
    hal_can_frame f;
    uint64_t release_us;  /* handed over from then on */
    uint32_t after;       /* reorder: or once more than this many frames have been handed over */
    bool reorder;
} fault_held;

typedef struct {
    /* The configuration may be changed between calls (a test opening a window now). */
    fault_can_config cfg;
    hal_can inner;
    fault_clock clock;
    fault_rng rng;
    fault_held held[FAULT_CAN_HOLD]; /* in the order they were held */
    unsigned nheld;
    fault_window counted;            /* the bus-off window last counted as an event */
    fault_can_stats stats;
} fault_can;

/* Wraps inner; time (for the windows and delays) starts now on clock. */
void fault_can_init(fault_can *fc, const fault_can_config *cfg, hal_can inner, hal_clock clock);
hal_can fault_can_hal(fault_can *fc);

#endif
