/* Homing's final move (homing.c) goes straight in slide space from where the switches left the
 * slides to the home pose's slides, every slide at the geometry's home_s.  Straight in slide space
 * is not straight for the plate, and between two valid ends it may pass poses the workspace's
 * margins refuse, or no pose at all (issue 24: home_sw_1 = 0.475 m, the others 0.2 m).  So it is
 * validated, as a move is, before the parameter check takes a set (fw_params_judge, from the
 * switches themselves) and before homing starts it (from where the slides are; in the controller's
 * thread, too long for the control tick: homing.h).
 *
 * The check: the plate's pose from the slides by forward kinematics, which is a pose only where
 * tse_ik takes it back with both margins, at FW_JOINT_PATH_SAMPLES + 1 points evenly spaced along
 * the path, walked from the home end (whose pose is known) each seeded with the last. */
#ifndef FW_JOINT_PATH_H
#define FW_JOINT_PATH_H

#include "tse/geometry.h"
#include "tse/status.h"

/* At 2.6k instructions a forward solve on the board, about 250k for the whole check: within a
 * frame's 2 ms (docs/validation.md, "What one frame costs").  Over homing's longest path, the
 * stroke, 0.4 m by default, 4 mm between points. */
#define FW_JOINT_PATH_SAMPLES 96u

/* TSE_OK when every point is a valid pose; otherwise the status of the first failing point found
 * from the home end, with its scissor and its position from the start in *where (0..1). */
tse_status fw_joint_path_check(const tse_geometry *g, const tse_real from[6], tse_real *where, int *scissor);

#endif
