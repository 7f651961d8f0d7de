/* The fixed-point inverse kinematics (tse/ik_fixed.h) in the kin target: the decoded design, pose
 * and seed rounded to the fixed formats, where they fit, and the answer checked against the double
 * build on exactly those numbers and against the reference. */
#ifndef FUZZ_KIN_FIXED_H
#define FUZZ_KIN_FIXED_H

#include "kin_input.h"

/* Runs the fixed IK on the case and checks it:
 *  - a design the fixed formats cannot hold, or that tse_fx_geometry_init refuses (its ranges are
 *    narrower than tse_params_check's), is a clean refusal naming a parameter; one it takes the
 *    double build takes too;
 *  - always: a valid status, a scissor 1..3 for a rejection and 0 for ok; `ok` has slides inside
 *    the stroke and mu, nu above their thresholds;
 *  - the double build's status (and scissor) on the same numbers wherever the reference is clear
 *    of its bands, and slides within 1 um of the double build's where it is well conditioned
 *    (mu >= 0.1, ref_well_conditioned).
 * A pose or seed the formats cannot hold (NaN, infinities, beyond +-128 m or +-8 rad, a seed
 * beyond the room: `invalid`) is refused, and that refusal is checked too. */
void kin_fixed_run(const kin_case *c);

#endif
