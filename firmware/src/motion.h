/* The control tick's motion: the running source (a move, with the one blended into it; a
 * trajectory; homing's joint move; homing's switch phase) advanced one control segment at a time
 * onto the step generator, and the controlled stop of whatever runs. */
#ifndef FW_MOTION_H
#define FW_MOTION_H

#include "controller_internal.h"

/* Starts a source the caller has prepared (tick.move, or the trajectory queue): state MOVING. */
void fw_motion_start(fw_controller *c, fw_source src);

/* A move planned from the end of the running one: blended into it from segment k0 (blend), or
 * run after it.  FW_START_BLENDED or FW_START_AFTER as it will run; FW_START_COUNT when it cannot
 * join (the running move is stopping, has a successor already, or is over). */
fw_move_start fw_motion_join(fw_controller *c, const fw_move *next, bool blend, uint32_t k0);

/* A controlled stop of whatever moves (homing included): state STOPPING. */
void fw_motion_stop(fw_controller *c);

typedef enum {
    FW_MOTION_RUNS,        /* a source runs, or its last setpoints are stepping out */
    FW_MOTION_AT_REST,     /* a motion ended here: the slides at their last setpoint */
    FW_MOTION_HOMING_ENDED /* homing ended here, homed or not (fw_homing) */
} fw_motion_outcome;

/* One control tick of motion: setpoints queued ahead for the step generator. */
fw_motion_outcome fw_motion_tick(fw_controller *c);

#endif
