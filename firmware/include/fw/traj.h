/* Timed trajectory points, streamed by the host with flow control: their validation as they
 * arrive (fw_traj_check), the queue that execution takes them from (fw_traj_queue), and the two
 * together (fw_traj) for a single user such as a host tool checking a file.  In the controller
 * the thread validates and the control tick owns the queue.
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

/* The validator's running state. */
typedef struct {
    fw_traj_point tail;     /* the newest point accepted (the start, at first) */
    bool closed;            /* the last point has been accepted */
    fw_slide_check chk;
    uint32_t next_segment;  /* next grid index the validator will sample */
} fw_traj_check;

/* The queue of validated points. */
typedef struct {
    fw_traj_point pts[FW_TRAJ_CAPACITY];
    unsigned head;          /* oldest queued point */
    unsigned count;
    fw_traj_point prev;     /* the point before the oldest queued one (the start, at first) */
    uint64_t end_us;        /* path time of the newest point ever queued */
    bool closed;            /* the last point is queued */
    bool dropped;           /* ended: takes no point until restarted */
} fw_traj_queue;

typedef struct {
    fw_traj_check check;
    fw_traj_queue queue;
} fw_traj;

/* Begins validating a trajectory at the current pose and slides, path time 0. */
void fw_traj_check_start(fw_traj_check *t, const fw_limits *lim, const tse_real pose[6], const tse_real q[6]);

/* Validates a point dt_us microseconds after the newest one: returns 0 with the point in *p and
 * the validator as it is once the point is taken in *after (t itself is not changed: assign
 * *after to it when the point is taken), or -1 with the reason in *res (FW_REASON_STATE after the
 * last point, FW_REASON_RANGE, FW_REASON_KINEMATICS with the first failing sample,
 * FW_REASON_TIMING with the slide and limit of the worst demand, its ratio to the limit over 1;
 * FW_REASON_STATE too when fw/work.h stops the walk). */
int fw_traj_check_point(const fw_traj_check *t, const tse_geometry *g, const fw_limits *lim, const tse_real pose[6],
                        uint32_t dt_us, bool last, fw_traj_point *p, fw_traj_check *after, fw_plan_result *res);

/* An empty queue starting at the current pose, path time 0. */
void fw_traj_queue_start(fw_traj_queue *q, const tse_real pose[6]);

/* Appends a validated point.  Returns 0, or -1 with FW_REASON_QUEUE_FULL, or FW_REASON_STATE once
 * dropped or after the last point (nothing is changed then). */
int fw_traj_queue_push(fw_traj_queue *q, const fw_traj_point *p, fw_reason *why);

/* Pose at path time tau_us; points reached leave the queue.  Returns false when tau_us is past
 * the newest point (the pose is then that point's). */
bool fw_traj_queue_pose(fw_traj_queue *q, uint64_t tau_us, tse_real pose[6]);

/* Ends the trajectory where it is: every queued point is dropped and none is taken any more until
 * fw_traj_queue_start begins the next one.  For a controller at rest after a stop, fault or
 * e-stop: nothing may run along it afterwards. */
void fw_traj_queue_drop(fw_traj_queue *q);

static inline unsigned fw_traj_queue_depth(const fw_traj_queue *q) { return q->count; }
static inline unsigned fw_traj_queue_free(const fw_traj_queue *q) { return FW_TRAJ_CAPACITY - q->count; }

/* The two together, for one user. */
void fw_traj_start(fw_traj *t, const fw_limits *lim, const tse_real pose[6], const tse_real q[6]);
/* Validates and appends: 0, or -1 with the reason in *res (those of both above); nothing is
 * changed then. */
int fw_traj_push(fw_traj *t, const tse_geometry *g, const fw_limits *lim, const tse_real pose[6],
                 uint32_t dt_us, bool last, fw_plan_result *res);
bool fw_traj_pose(fw_traj *t, uint64_t tau_us, tse_real pose[6]);
void fw_traj_drop(fw_traj *t);
/* Path time of the newest point [us]. */
uint64_t fw_traj_end_us(const fw_traj *t);

static inline unsigned fw_traj_depth(const fw_traj *t) { return t->queue.count; }
static inline unsigned fw_traj_free(const fw_traj *t) { return FW_TRAJ_CAPACITY - t->queue.count; }

#endif
