/* Shortcuts into states that take long to reach honestly, for tests and benchmarks only (never a
 * platform): each does what the controller's own path would leave, at rest, where nothing runs at
 * once. */
#ifndef FW_TESTING_H
#define FW_TESTING_H

#include <stdint.h>

#include "fw/controller.h"
#include "fw/params.h"
#include "fw/traj.h"

/* The step generator's count of each slide, as homing's zero would set it.  Returns 0, or -1 when
 * the generator is not at rest. */
int fw_testing_set_positions(fw_controller *c, const int32_t pos[6]);

/* Homed at the home pose, as homing leaves the controller (its slides counted there): for a
 * benchmark whose fake HAL has no switches.  Returns 0, or -1 when not at rest. */
int fw_testing_homed_at_home(fw_controller *c);

/* The same at pose p, its slides there: for a benchmark's commits from anywhere.  Returns 0, or -1
 * when not at rest or p has no inverse kinematic solution. */
int fw_testing_homed_at(fw_controller *c, const tse_real p[6]);

/* One parameter written past the parameter check into both contexts' copies, as a defect or a
 * corrupted store would leave it: for the tests that what the check guards is guarded again where
 * it is used (homing's final move, fw/joint_path.h).  Only at rest. */
void fw_testing_force_param(fw_controller *c, fw_param_id id, int32_t value);

/* A point left in the trajectory queue with no trajectory open (as a fault latch once left it):
 * for the test that a STOP at rest drops it. */
void fw_testing_hold_point(fw_controller *c, const fw_traj_point *p);

/* A segment the step generator could not step in its time, counted as its step interrupt counts
 * one (stepgen.overruns): for the test that an overrun is a fault. */
void fw_testing_overrun(fw_controller *c);

#endif
