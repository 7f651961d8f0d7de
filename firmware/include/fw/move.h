/* A point-to-point move of the plate: straight in position, orientation by slerp, under one
 * jerk-limited profile of the path parameter u in [0, 1].
 *
 * Planning validates the whole path before the first step, at the control segment rate, with
 * the inverse kinematics warm-started from segment to segment exactly as execution will run it:
 * every segment reachable with both singularity margins; slide speeds within their limit (and
 * the step rate); slide accelerations within theirs.  A path that leaves the workspace is
 * rejected with its first failing point; one that is only too fast is stretched in time.  Planning
 * holds the slides to 95 % of their limits, for the step quantisation; a move still
 * too fast after every stretch is refused with TIMING, its ratio against the limits in effect (so
 * it may be from 0.95 up). */
#ifndef FW_MOVE_H
#define FW_MOVE_H

#include <stdbool.h>
#include <stdint.h>

#include "fw/path.h"
#include "fw/profile.h"
#include "fw/slide_check.h"
#include "fw/types.h"
#include "fw/validate.h"
#include "tse/ik.h"

typedef enum { FW_MOVE_DURATION = 0, FW_MOVE_SPEED = 1 } fw_move_kind;


/* A result with no reason and every field 0. */
void fw_plan_clear(fw_plan_result *res);

/* A TIMING refusal naming the worst demand w of a slide check whose limits were `scale` times
 * lim's (so the ratio against lim's is scale times w's), and the limit that is (lim->vmax_by for a
 * speed). */
void fw_plan_timing(fw_plan_result *res, fw_slide_worst w, tse_real scale, const fw_limits *lim);

/* Plans from pose `from` (whose slides are q_from) to `to`.  kind/value: the duration [s], or the
 * plate speed [m/s] (rotation-only moves then use the angular limit).  Returns 0 on success, with
 * what set the pace in bound, bound_slide and bound_ratio. */
int fw_move_plan(fw_move *mv, const tse_geometry *g, const fw_limits *lim, const tse_real from[6],
                 const tse_real to[6], fw_move_kind kind, tse_real value, const tse_real q_from[6],
                 fw_plan_result *res);

/* fw_move_plan with the validation given (fw/validate.h): the tests compare the two. */
int fw_move_plan_by(fw_move *mv, const tse_geometry *g, const fw_limits *lim, const tse_real from[6],
                    const tse_real to[6], fw_move_kind kind, tse_real value, const tse_real q_from[6],
                    fw_plan_result *res, fw_validator validate);

/* Blending a second move into a running one, without stopping between them.
 *
 * b was planned from a's end pose (fw_move_plan, from rest: the fallback).  The blend starts b
 * during a's deceleration, at segment k0 of a, so that the two overlap for min(a's ramp, b's
 * ramp) and end together with a's end: positions add, b's rotation composes onto a's.  The whole
 * of a then b is walked as execution will run it; if the blend leaves the workspace or a slide
 * limit, or k0 would be before `earliest`, *k0 = a->segments (back to back) and 1 is returned;
 * 0 when the blend holds. */
int fw_move_blend(const fw_move *a, const fw_move *b, const tse_geometry *g, const fw_limits *lim,
                  uint32_t earliest, uint32_t *k0);

/* Pose at time t of a's clock when b starts at segment k0 of a. */
void fw_move_blend_pose(const fw_move *a, const fw_move *b, uint32_t k0, const fw_limits *lim, tse_real t,
                        tse_real pose[6]);

#endif
