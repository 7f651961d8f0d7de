/* The path of a point-to-point move, as planning (fw/move.h) and validation (fw/validate.h) both
 * walk it: the move's description, the limits it is held to, why a path is refused, and the two
 * facts they share - the pose at a time or a path parameter, and the time of each control
 * segment's end.  Planning builds a move; validation and execution read it through these. */
#ifndef FW_PATH_H
#define FW_PATH_H

#include <stdbool.h>
#include <stdint.h>

#include "fw/profile.h"
#include "fw/slide_check.h"
#include "fw/types.h"
#include "tse/ik.h"

/* The limit a slide's demand is held to: REJECT's field for a timing refusal carries it times 16
 * (fw/reject.h; proto_slide_limits words each).  Wire values: append, never renumber. */
typedef enum {
    FW_LIMIT_SLIDE_VMAX = 0,     /* the speed limit, slide_vmax itself */
    FW_LIMIT_SLIDE_AMAX = 1,     /* the acceleration limit, slide_amax */
    FW_LIMIT_STEP_GENERATOR = 2, /* the speed limit set by the step generator (fw/limits.h) */
    FW_LIMIT_COUNT
} fw_slide_limit;

typedef struct {
    tse_real slide_vmax, slide_amax;             /* m/s, m/s^2 (step rate already folded in) */
    tse_real plate_vmax, plate_amax, plate_jmax; /* m/s, m/s^2, m/s^3 */
    tse_real plate_wmax, plate_dwmax;            /* rad/s, rad/s^2 */
    tse_real segment_hz;                         /* control segments per second */
    fw_slide_limit vmax_by;                      /* what sets slide_vmax (fw_limits_from_params) */
} fw_limits;

/* The share of slide_amax a path may use: moves are planned, trajectory rows validated, within it.
 * The rest keeps the rounding to whole steps and a stop's braking within the limit: a stop ramp
 * slows the path's clock, and its braking adds to the path's own acceleration (firmware/src/motion.c
 * sizes the ramp so that the two together stay below slide_amax). */
#define FW_PATH_MARGIN TSE_R(0.95)

typedef struct {
    tse_real from[6], to[6];
    tse_real dp[3];     /* displacement of the plate centre */
    tse_real q0[4], q1[4];
    tse_real length;    /* |dp| [m] */
    tse_real angle;     /* rotation [rad] */
    tse_real omega[3];  /* the plate's world angular velocity per unit of u [rad]: constant */
    fw_profile prof;    /* of u, D = 1 */
    uint32_t segments;  /* control segments; the last one ends exactly at prof.T */
    tse_real stretch;   /* time factor the slide limits imposed (1: none) */
    uint8_t bound;      /* fw_move_bound: what set the pace */
    uint8_t bound_slide;/* for a slide bound, the slide 1..6 (A1, B1, A2, B2, A3, B3); else 0 */
    tse_real bound_ratio; /* for a slide bound, its demand at the pace before the stretch (the
                           * request's, or the plate limits' where slower) over its limit
                           * parameter (> 1); else 0 */
    tse_real v_peak;    /* the fastest any slide goes along it [m/s], as validation found */
    tse_real q_from[6]; /* slides at the start */
    tse_real q_end[6];  /* slides at the end, as validation solved them */
} fw_move;

/* Why a path was refused.  Fields that do not belong to the reason are 0. */
typedef struct {
    fw_reason reason;  /* NONE, KINEMATICS, RANGE (a bad request), TIMING, TOO_LONG (a move longer
                        * than FW_MOVE_MAX_S, or too long to prove near a limit: fw/validate.h) */
    tse_status status; /* KINEMATICS: kinematic status of the first failing point; TOO_LONG: TSE_OK
                        * for a move longer than FW_MOVE_MAX_S, else the limit the proof stopped at */
    int scissor;       /* KINEMATICS: its first failing scissor; TIMING: the scissor of `slide` (1..3);
                        * TOO_LONG near a limit: the scissor the proof stopped at */
    uint32_t segment;  /* KINEMATICS: first failing segment */
    tse_real where;    /* KINEMATICS, TOO_LONG near a limit: its u, 0..1; TOO_LONG in time:
                        * FW_MOVE_MAX_S */
    uint8_t slide;     /* TIMING: the slide with the worst demand, 1..6 (A1, B1, A2, B2, A3, B3) */
    bool accel;        /* TIMING: that demand is an acceleration (else a speed) */
    fw_slide_limit limit; /* TIMING: the limit it is against (FW_LIMIT_SLIDE_AMAX when accel) */
    tse_real ratio;    /* TIMING: the demand over that limit (1: at the limit) */
} fw_plan_result;

/* Pose at time t (clamped to the move). */
void fw_move_pose(const fw_move *mv, tse_real t, tse_real pose[6]);

/* Pose at path parameter u in [0, 1]: the straight line and the slerp. */
void fw_move_pose_at(const fw_move *mv, tse_real u, tse_real pose[6]);

/* Time of control segment k's end: k / rate, the last one exactly at the end. */
tse_real fw_move_segment_time(const fw_move *mv, const fw_limits *lim, uint32_t k);

#endif
