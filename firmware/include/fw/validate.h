/* Validation of a planned move before its first step: every control segment's pose reachable with
 * both singularity margins (as tse_ik checks it), and the slides' speed and acceleration, as the
 * per-segment setpoints will produce them, within the limits.
 *
 * Two ways to the same verdict:
 * - fw_validate_per_segment solves the inverse kinematics at every segment, warm-started as
 *   execution will run it, and measures the setpoints' differences (fw_slide_check).  It costs one
 *   solve per segment: 5,000 for a 5 s move, too slow for a commit on the board.
 * - fw_validate proves whole pieces of the path at once (tse/enclose.h): for a piece of the
 *   profile's segments it solves the centre pose and encloses the solution of every pose of the
 *   piece in a box that passes every check, with bounds on the slides' first and second
 *   derivatives along the path; a piece that cannot be proven is halved.  A piece of one segment
 *   that still cannot be proven is settled as the per-segment walk settles it: its end pose is
 *   solved and checked, so a path is refused exactly where that walk refuses it.  The slides'
 *   speed over a piece is at most sup|dq/du| sup(du/dt) and their acceleration at most
 *   sup|d2q/du2| sup(du/dt)^2 + sup|dq/du| sup|d2u/dt2|; a setpoint difference over a segment
 *   (or the stride of fw_slide_check) is an average of those derivatives (the setpoints hold
 *   still before the start and after the end, where the profile is at rest), so it is bounded by
 *   them.  What the per-segment walk also measures is the solver's rounding in the setpoints
 *   (below 3e-7 m in float, against 0.8 um steps), which the planning margin covers as it covers
 *   the steps.  When a proof cannot even enclose the solution of a one-segment piece (a pose at a
 *   singularity, a branch it cannot follow), fw_validate falls back to the per-segment walk.
 * docs/validation.md has the argument in full. */
#ifndef FW_VALIDATE_H
#define FW_VALIDATE_H

#include <stdbool.h>
#include <stdint.h>

#include "fw/path.h"
#include "fw/slide_check.h"

typedef struct {
    tse_real v_ratio, a_ratio; /* worst speed and acceleration over the limits given */
    uint8_t v_slide, a_slide;  /* the slides (q index 0..5) of each */
    fw_slide_worst worst;      /* the worse of the two and its slide */
    tse_real q_end[6];         /* slides at the move's end pose */
    uint32_t pieces;           /* pieces tried (fw_validate) */
    uint32_t solves;           /* inverse kinematics solved */
    bool per_segment;          /* the verdict came from the per-segment walk */
    bool unproven;             /* refused because the proof could not finish (fw_validate) */
} fw_validation;

/* The work a validation did, in inverse kinematic solves: a piece's enclosure costs about as much
 * as five (on the board: 1.2k instructions a solve, 6.5k an enclosure). */
#define FW_PIECE_WORK 6u
uint32_t fw_validation_work(const fw_validation *v);

/* What bounds fw_validate's time whatever the move's duration: the work it does at most
 * (fw_validation_work), and the longest move, in segments, it walks segment by segment when its
 * proof cannot finish within the rest. */
#define FW_VALIDATE_WORK 8192u
#define FW_VALIDATE_WALK 4096u

/* Both return 0 with *v filled, or -1 with the first failing segment in *res (KINEMATICS); or
 * fw_validate -1 with TOO_LONG in *res for a path longer than FW_VALIDATE_WALK segments that its
 * proof could not finish within FW_VALIDATE_WORK (v->unproven).
 * vmax, amax: the slide limits to measure against (the planner passes them with its margin). */
int fw_validate_per_segment(const fw_move *mv, const tse_geometry *g, const fw_limits *lim,
                            const tse_real q_from[6], fw_validation *v, fw_plan_result *res);
int fw_validate(const fw_move *mv, const tse_geometry *g, const fw_limits *lim, const tse_real q_from[6],
                fw_validation *v, fw_plan_result *res);

/* One of the two above. */
typedef int (*fw_validator)(const fw_move *mv, const tse_geometry *g, const fw_limits *lim,
                            const tse_real q_from[6], fw_validation *v, fw_plan_result *res);

#endif
