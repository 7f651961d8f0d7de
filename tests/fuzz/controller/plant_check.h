/* What the plant sees, judged as the simulator's plant judges a real robot (docs/controller.md,
 * "What the simulator's plant checks"): the stroke, the slide speed, the step rate and the DIR
 * set-up, and no step without energised drives in a state that moves the robot.  Fed from the
 * rig's stepper wrapper (every pulse and direction write) and at every control-segment boundary. */
#ifndef FUZZ_CONTROLLER_PLANT_CHECK_H
#define FUZZ_CONTROLLER_PLANT_CHECK_H

#include <stdbool.h>
#include <stdint.h>

#include "rig.h"

/* Takes the parameter set in force (the oracle's model of it) and forgets the history (pulse and
 * direction times, the speed window): at the start, after a reboot and on every change of the set. */
void plant_check_reset(const rig *r, const fw_param_set *params);

/* A direction write at the current tick (before the fake takes it). */
void plant_check_dir(const rig *r, uint8_t forward_mask);

/* Step pulses at the current tick (before the fake counts them).  estop_cut: an e-stop interrupt
 * has fired and the controller has not yet entered ESTOP. */
void plant_check_pulse(const rig *r, uint8_t mask, bool estop_cut);

/* Slides whose zero the controller had to take from a switch the rig forced (a lying switch):
 * their coordinates are the controller's best, not the plant's, until the next homing. */
void plant_check_zero_suspect(uint8_t mask);

/* At a control-segment boundary: the slides' travel over the last segment period, and the stroke. */
void plant_check_segment(const rig *r);

/* The stroke alone, once homed. */
void plant_check_stroke(const rig *r);

#endif
