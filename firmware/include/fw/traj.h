/* A queue of timed trajectory points, streamed by the host with flow control.
 *
 * Between points the plate moves straight in position with the orientation slerped, at the pace
 * the points' times set.  Each point is validated as it arrives, on the very time grid execution
 * will sample (multiples of the segment period from the trajectory's start), with the inverse
 * kinematics seeded along the same chain: reachable with both margins, and the slides within their
 * speed and acceleration limits, counting the rest before the first point and, once the last
 * point is flagged, the rest after it.  A timed point cannot be stretched: too fast is refused. */
#ifndef FW_TRAJ_H
#define FW_TRAJ_H

#include <stdbool.h>
#include <stdint.h>

#include "fw/move.h"
#include "fw/slide_check.h"

#define FW_TRAJ_CAPACITY 32u

typedef struct {
    tse_real pose[6];
    tse_real q0[4];   /* its orientation as a quaternion (hemisphere continuous along the queue) */
    uint64_t t_us;    /* path time of the point: integer microseconds, so that comparisons with
                       * the segment grid are exact */
    tse_real v_peak;  /* the fastest any slide goes over the piece ending here [m/s], as its
                       * validation's setpoints measured it: what a stop along it must brake */
    bool last;
} fw_traj_point;

typedef struct {
    fw_traj_point pts[FW_TRAJ_CAPACITY];
    unsigned head;          /* oldest queued point */
    unsigned count;
    fw_traj_point prev;     /* the point before the oldest queued one (the start, at first) */
    fw_traj_point tail;     /* the newest point ever accepted */
    bool closed;            /* the last point has been accepted */
    fw_slide_check chk;     /* the validator's running state */
    uint32_t next_segment;  /* next grid index the validator will sample */
} fw_traj;

/* Begins an empty trajectory at the current pose and slides, path time 0. */
void fw_traj_start(fw_traj *t, const fw_limits *lim, const tse_real pose[6], const tse_real q[6]);

/* Validates and appends a point dt_us microseconds after the newest one.  Returns 0, or -1 with the
 * reason in *res (FW_REASON_QUEUE_FULL, FW_REASON_STATE after the last point or once dropped,
 * FW_REASON_KINEMATICS with the first failing sample, FW_REASON_TIMING with the slide and limit
 * of the worst demand, its ratio to the limit over 1); nothing is changed then. */
int fw_traj_push(fw_traj *t, const tse_geometry *g, const fw_limits *lim, const tse_real pose[6],
                 uint32_t dt_us, bool last, fw_plan_result *res);

/* Ends the trajectory where it is: every queued point is dropped and no point is accepted for it
 * any more (fw_traj_push refuses with FW_REASON_STATE) until fw_traj_start begins the next one.
 * For a controller at rest after a stop, fault or e-stop: nothing may run along it afterwards. */
void fw_traj_drop(fw_traj *t);

/* Pose at path time tau_us; points reached leave the queue.  Returns false when tau_us is past
 * the newest point (the pose is then that point's). */
bool fw_traj_pose(fw_traj *t, uint64_t tau_us, tse_real pose[6]);

/* Path time of the newest point [us]. */
uint64_t fw_traj_end_us(const fw_traj *t);

static inline unsigned fw_traj_depth(const fw_traj *t) { return t->count; }
static inline unsigned fw_traj_free(const fw_traj *t) { return FW_TRAJ_CAPACITY - t->count; }

#endif
