/* What the planner's tests share: a plan made in memory of its own, and the rows judged by the
 * controller's validator directly (traj_checker), independently of the planner's own check. */
#ifndef PLAN_SUPPORT_H
#define PLAN_SUPPORT_H

#include "fw/limits.h"
#include "plan/plan.h"

/* Plans wp[0..n) under the default parameters (set may be NULL) with options o (NULL: defaults).
 * Returns the plan (free_plan it) or NULL with *r. */
plan *make_plan(const fw_param_set *set, const plan_waypoint *wp, int n, const plan_options *o, plan_result *r);
void free_plan(plan *p);

/* The waypoint at pose, free in time and speed. */
plan_waypoint waypoint(double x, double y, double z, double roll, double pitch, double yaw);

typedef struct {
    int refused_row;  /* -1: every row accepted */
    long rows_mid;    /* rows outside the first and last 5 % of the motion's time (after the hold) */
    long rows_near;   /* of those, rows with some slide at >= 90 % of its speed or acceleration limit */
    double v_peak, a_peak;
} judged;

/* Every row of p through the validator of a controller at the built-in rates from rest at the first
 * waypoint (its slides solved here), with each row's own worst demand. */
judged judge_rows(const fw_param_set *set, const plan *p, const double pose0[6]);
/* The same for a controller at rates r. */
judged judge_rows_at(const fw_param_set *set, fw_rates r, const plan *p, const double pose0[6]);

#endif
