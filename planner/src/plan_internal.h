/* The planner's parts and the plan they share (plan.h is the promise). */
#ifndef PLAN_INTERNAL_H
#define PLAN_INTERNAL_H

#include "fw/limits.h"
#include "plan/plan.h"
#include "traj_checker.h"
#include "tse/geometry.h"

#define PLAN_PI 3.14159265358979323846

/* The geometric path: pose(s) for s in [0, length], with its first and second derivatives. */
typedef struct {
    double p0[6], p1[6], p2[6]; /* a line p0 -> p1 (p2 unused), or a quadratic blend p0, p1, p2 */
    double s0, len;             /* where it starts along the path, and its length there */
    bool blend;
} plan_piece;

typedef struct {
    int n;              /* waypoints */
    double length;      /* [m] */
    double r_top;       /* weight of an angle in lengths [m/rad] */
    double *ws;         /* [n] s where each waypoint is passed */
    /* Spline (blend == 0): values (angles unwrapped) and second derivatives at the knots ws. */
    double (*val)[6], (*m2)[6];
    /* Blend: the pieces. */
    plan_piece *pieces;
    int n_pieces;
} plan_path;

/* The interval of the sorted a[0..n) (n >= 2) that holds x: the last i <= n - 2 with a[i] <= x
 * (0 when x is below a[0]). */
long plan_interval(const double *a, long n, double x);

/* Builds the path through wp[0..n) in the arrays already pointed to (n knots, 2n pieces).  Returns
 * 0, or -1 with r filled (a waypoint that repeats the one before). */
int plan_path_build(plan_path *path, const plan_waypoint *wp, int n, double blend, plan_result *r);

/* Pose and its derivatives along s at s (clamped); angles wrapped to (-pi, pi] in p, unwrapped in
 * the derivatives' sense.  Any of dp, ddp may be NULL. */
void plan_path_eval(const plan_path *path, double s, double p[6], double dp[6], double ddp[6]);

/* The grid: N + 1 points h apart; at each the slides' first and second derivatives along s. */
typedef struct {
    long N;
    double h;
    double (*qs)[6], (*qss)[6];
    double (*qsj)[6]; /* the part of q_ss from the Jacobian's change alone (J' p' p', without J p''):
                       * what makes a slide's speed vary along a straight row (plan_time_law) */
    double *vcap2;   /* the square of the path speed the plate speed caps allow (INFINITY: none) */
    double *slow;    /* the share of the limits allowed there (1, lower where the validator refused) */
    int *stretch;    /* the waypoint each point's stretch starts at */
    double *K;       /* the backward pass: the greatest s'^2 from which the end is reachable */
    double *x;       /* the forward pass: s'^2 */
    double *t;       /* time at each point [s] */
    double *xs, *ts; /* scratch: the smoothed law's s'^2 and times (plan_jerk_smooth) */
    double *cap;     /* a cap on s'^2 that smoothing the law needs (plan_time_law; INFINITY: none) */
} plan_grid;

struct plan {
    const plan_waypoint *wp;
    int n;
    plan_options opt;
    tse_geometry g;
    fw_limits lim;
    fw_param_set set;
    double vlim, alim;     /* the limits planned for (margins, and the rows' acceleration rule) */
    double jmax;           /* the slides' jerk limit planned for (0: none) */
    double tj;             /* the jerk window the last law was smoothed over [s] (plan_jerk_smooth) */
    double row_f;          /* min(1, the validator's acceleration stride / period) */
    double q0[6];          /* slides at the first waypoint */
    plan_path path;
    plan_grid grid;
    int64_t *tw_us;        /* [n] the time each waypoint is passed [us] */
    double *pace;          /* [n] the share of the limits each stretch is held to, keeping the
                            * waypoints' times (1 where no time is given) */
    int64_t period_us;
    int64_t hold_us;       /* the first row's time: the motion starts there */
    int64_t min_us;        /* the rows' least spacing (plan_row_spacing_min) */
    long rows;
    int retries;
    traj_checker chk;
};

/* Solves every grid point (and first every waypoint) and fills qs, qss and vcap2.  Returns 0, or
 * -1 with r (WORKSPACE) filled. */
int plan_grid_solve(plan *p, plan_result *r);

/* The time law over the grid under the limits and slow[]: K, x, t; then tw_us and rows.  Returns
 * 0, or -1 when the path cannot move (r filled). */
int plan_time_law(plan *p, plan_result *r);

/* Smooths the law x (with its times t) to one whose slides keep to p->jmax (> 0), x and t anew:
 * the path speed averaged over a window, p->tj. */
void plan_jerk_smooth(plan *p);

/* Pose at time t [s] of the time law. */
void plan_pose_at(const plan *p, double t, double pose[6]);

/* Runs the rows through the validator from rest at the first waypoint.  Returns 0, or 1 with the
 * refused row's index and REJECT in r (status REFUSED). */
int plan_validate(plan *p, plan_result *r);

#endif
