/* From waypoint poses to a trajectory the controller accepts, near the fastest its slides allow.
 *
 * The path: a smooth curve through the waypoints (a natural cubic spline in the pose's six
 * coordinates, parameterised by chord length, so it passes through each one), or, with a blend
 * tolerance, straight pieces between them whose corners are cut by at most that much (a quadratic
 * blend, LinuxCNC's G64 P).  Lengths along it weigh rotation as the travel of the plate's ball
 * joints (r_top times the angle), as the kinematics' Jacobian does.
 *
 * The time law: a reachability analysis over a grid of path points (TOPP-RA, Pham and Pham 2018):
 * the slides' speed and acceleration limits act on the path speed through the inverse kinematics'
 * Jacobian (q' = J p', q'' = q' s'' + q_ss s'^2), a backward pass bounds the path speed every point
 * can still stop from, a forward pass takes the greatest acceleration that stays within it.  The
 * limits are the controller's own (fw/limits.h: slide_vmax and the step generator's bound,
 * slide_amax), as its trajectory validator measures them on the rows (fw/traj.h): rows period
 * apart and straight between them, so a row may change a slide's speed by at most
 * slide_amax x the validator's acceleration stride (10 ms): rows more than 10 ms apart plan at
 * slide_amax x 10 ms / period.  There is a row at the time each waypoint is passed, so the
 * controller's path goes through every waypoint too, and between two waypoints' rows the fewest
 * rows evenly spaced at most `period` apart.
 *
 * Every point of the grid is solved (tse_ik, the controller's own checks): a path that leaves the
 * workspace (stroke, angle stops, either singularity margin) is refused naming the waypoint, or the
 * two it runs between.  The rows are then run through the controller's validator from rest at the
 * first waypoint (host_tools/traj_check, what tsectl checks a file with); where it refuses, that
 * stretch is slowed and the plan made again, a bounded number of times: a plan is never returned
 * that the validator refuses.
 *
 * A waypoint's time (t) holds the stretch before it to the share of the limits that passes it then
 * (a bisection); a speed cap (v) bounds the plate's speed from it on.  No jerk limit: the
 * controller's trajectory validator holds rows to speed and acceleration only, and so does this.
 *
 * No heap: the caller gives the memory (plan_bytes says how much).  Host only (double). */
#ifndef PLAN_PLAN_H
#define PLAN_PLAN_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "fw/limits.h"
#include "fw/params.h"
#include "fw/proto_table.h"
#include "fw/traj.h"
#include "tse/status.h"

/* Grid spacing along the path [m], and the fewest grid points. */
#define PLAN_GRID_STEP 0.0005
#define PLAN_GRID_MIN 64
/* Most grid points (a path of 1 km at PLAN_GRID_STEP) and waypoints. */
#define PLAN_GRID_MAX 2000000L
#define PLAN_WAYPOINTS_MAX 100000
/* Rows' spacing: --period's range [s], and its default. */
#define PLAN_PERIOD_MIN 0.001
#define PLAN_PERIOD_MAX 1.0
#define PLAN_PERIOD_DEFAULT 0.02
/* The largest blend tolerance [m]. */
#define PLAN_BLEND_MAX 1.0
/* The largest jerk limit [m/s^3] (beyond it the smoothing window is below a control period), and
 * the jmax that asks for the controller's own (fw_slide_jmax: slide_amax x plate_jmax /
 * plate_amax, which its moves and homing keep to). */
#define PLAN_JERK_MAX 1e6
#define PLAN_JMAX_CONTROLLER (-1.0)
/* Plans made again after a refusal, at most. */
#define PLAN_RETRIES_DEFAULT 40
/* The wire's least dt between rows [us]. */
#define PLAN_ROW_MIN_US 1000
/* The controller stops a trajectory whose queue holds less path than a stop from the speeds queued
 * needs (an underrun: docs/controller.md, "Faults" and "Stops"): the path its stop ramp covers from
 * the fastest slide speed v (fw/traj_stop.h: 2.27 v / slide_amax), and two control periods.  The
 * host keeps its queue of FW_TRAJ_CAPACITY rows full less the rows in flight, so rows closer than
 * (that path + margin) / PLAN_QUEUED_ROWS at the speed limit would leave too little path queued:
 * the planner's rows are never closer (a waypoint passed sooner after the previous row has no row
 * of its own), and a --period below that is refused. */
#define PLAN_QUEUED_ROWS (FW_TRAJ_CAPACITY - PROTO_TRAJ_WINDOW)
#define PLAN_QUEUE_MARGIN_S 0.012

typedef struct {
    double pose[6]; /* x, y, z [m], roll, pitch, yaw [rad] */
    double t;       /* the time the plate passes it [s]; NAN: free (the first one's is 0) */
    double v;       /* the plate's speed from here to the next waypoint at most [m/s]; NAN: none */
    int line;       /* where it came from (for messages; 0: none) */
    int number;     /* what messages call it: waypoint `number`; 0: its place in the array (from 1);
                     * -1: the plate's pose where the path starts (not the user's) */
} plan_waypoint;

typedef struct {
    double period;   /* rows' spacing [s] */
    double blend;    /* 0: a spline through every waypoint; > 0: straight pieces, corners cut by at
                      * most this much [m] */
    int retries;     /* plans made again after the validator refuses, at most */
    double v_margin; /* the share of the speed limit planned for (the rest covers the rows' rounding) */
    double a_margin; /* the same for the acceleration limit */
    double jmax;     /* a jerk limit for the slides [m/s^3] up to PLAN_JERK_MAX, PLAN_JMAX_CONTROLLER
                      * for the controller's own, or 0 (the default): none.  The controller bounds no
                      * trajectory's jerk (its rows are straight: each changes the speed at once, and
                      * the validator judges acceleration over 10 ms); a limit smooths the time law to
                      * it (plan_jerk_smooth) */
    fw_rates rates;  /* the controller's rates, which its limits follow (INFO's; by default
                      * FW_RATES_BUILT_IN, for planning offline) */
} plan_options;

void plan_options_default(plan_options *o);

typedef enum {
    PLAN_OK = 0,
    PLAN_BAD_INPUT,  /* the options or the waypoints themselves (what: in `why`) */
    PLAN_PARAMS,     /* the controller would refuse the parameter set (or cannot run at the rates) */
    PLAN_WORKSPACE,  /* a waypoint, or the path between two, leaves the workspace */
    PLAN_TIME,       /* a waypoint's time cannot be kept */
    PLAN_TOO_LONG,   /* more grid points than PLAN_GRID_MAX, or memory short (plan_bytes) */
    PLAN_REFUSED     /* the validator still refused after every retry */
} plan_status;

typedef struct {
    plan_status status;
    int waypoint;         /* 0-based waypoint at fault (WORKSPACE, TIME, BAD_INPUT), or -1 */
    bool between;         /* WORKSPACE: on the way from `waypoint` to the next, not at it */
    double at;            /* WORKSPACE between two: how far along, 0..1 */
    tse_status kin;       /* WORKSPACE: the kinematic status */
    int scissor;          /* and its first failing scissor (1..3) */
    double t_needed;      /* TIME: the earliest the waypoint can be reached [s] */
    long row;             /* REFUSED: the 0-based row refused */
    int32_t reject[PROTO_MAX_FIELDS]; /* REFUSED: the REJECT the controller would send for it */
    int retries;          /* plans made again */
    const char *why;      /* BAD_INPUT: what is wrong (a constant string) */
    double period_min;    /* BAD_INPUT for a period too short: the least [s] */
} plan_result;

typedef struct plan plan;

/* The memory plan_make needs for these waypoints and options under set s (0 for input or a set it
 * refuses: plan_make says why). */
size_t plan_bytes(const fw_param_set *s, const plan_waypoint *wp, int n, const plan_options *o);

/* Plans wp[0..n) under parameter set s in mem[0..bytes) (8-byte aligned).  Returns the plan (in
 * mem, valid while mem is and wp is unchanged), or NULL with *r saying why. */
plan *plan_make(void *mem, size_t bytes, const fw_param_set *s, const plan_waypoint *wp, int n,
                const plan_options *o, plan_result *r);

/* The rows: t [s, whole microseconds] after the start, pose [m, rad].  The first holds the first
 * waypoint traj_lead after the start (at least 1 ms): the controller starts its clock on it, and the
 * plate waits at rest there while the host fills the queue ahead of the motion (the motion's first
 * rows, a queue of the controller's lead only, would hold too little path for a stop once the plate
 * is fast).  Waypoints' times count from the start (a given t of 0.5 s is passed at row time 0.5 s). */
typedef struct {
    double t;
    double pose[6];
} plan_row;

typedef struct {
    int a, b;      /* the stretch between the rows of waypoints a and b */
    long j, m;     /* the next of its m rows */
    bool held;     /* the first row (the hold) is out */
    bool done;
} plan_cursor;

void plan_rows_begin(const plan *p, plan_cursor *c);
/* The next row: 1, or 0 after the last. */
int plan_rows_next(const plan *p, plan_cursor *c, plan_row *row);

double plan_duration(const plan *p); /* [s]: the last row's time */
long plan_row_count(const plan *p);
/* The times the validator refused a row and the stretch around it was slowed. */
int plan_retries(const plan *p);
/* The last waypoint passed at row time t [s] (0-based): what a message about a row names. */
int plan_row_waypoint(const plan *p, double t);
/* The first row's time [s]: where the motion starts. */
double plan_hold(const plan *p);
/* The rows' least spacing [s] (the controller's queue and its stop ramp) under set s at rates r. */
double plan_row_spacing_min(const fw_param_set *s, fw_rates r);
/* The slides at the first waypoint (where the validator starts). */
void plan_start_slides(const plan *p, double q[6]);

/* How near the rows come to the limits, as the controller's validator measures them. */
typedef struct {
    double v_peak, a_peak;  /* the worst speed and acceleration over their limits (1: at it) */
    double j_peak, j_limit; /* planned with a jerk limit (j_limit [m/s^3], the controller's in figures;
                             * else 0): the worst jerk over it, by third differences of the slides at
                             * four rows evenly apart */
    double v_limit, a_limit;/* the limits in effect [m/s, m/s^2] */
    long rows_mid;          /* rows outside the first and last 5 % of the motion's time (after the hold) */
    long rows_near;         /* of those, rows with some slide at 90 % or more of a limit (jerk's too) */
} plan_stats;

/* Measures the rows of p.  Returns 0, or -1 when the validator refuses a row (not for a plan
 * plan_make returned). */
int plan_measure(const plan *p, plan_stats *st);

/* The result in words, e.g. "waypoint 3 (line 5): a slide leaves its stroke (scissor 2)". */
const char *plan_explain(const plan_result *r, const plan_waypoint *wp, char *buf, size_t cap);

#endif
