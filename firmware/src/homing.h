/* Homing as a motion source of the control tick: every slide finds the release edge of its low
 * switch on its own, then all six go to the home pose in a joint-space move (which the tick runs
 * like any source, motion.c) once the thread has checked its path.  Homing changes no state but its own and the motion it starts; what
 * it comes to is its caller's to act on. */
#ifndef FW_HOMING_H
#define FW_HOMING_H

#include "controller_internal.h"

/* Begins homing from wherever the slides are (state HOMING, no zero, no pose). */
void fw_homing_start(fw_controller *c);

typedef enum {
    FW_HOMING_GOING,  /* still finding the switches, or the joint move just began (src JOINT) */
    FW_HOMING_ENDED   /* at rest and over: homed (at the home pose), or stopped short (not) */
} fw_homing_outcome;

/* One control tick of homing while no source runs: the switch phase, the wait for the check of
 * the joint move's path, or the end once the joint move is over. */
fw_homing_outcome fw_homing_tick(fw_controller *c);

/* From the thread: the check of the joint move's path the tick asked for, if any (fw/joint_path.h:
 * about 250k instructions on the board, too long for the control tick's 50 us). */
void fw_homing_check_path(fw_controller *c);

#endif
