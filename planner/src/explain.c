/* A planner's refusal in words, naming the waypoint (and its line) and the reason. */
#include <math.h>
#include <stdio.h>

#include "plan/plan.h"

static const char *kin_words(tse_status s)
{
    switch (s) {
    case TSE_STROKE:
        return "a slide would leave its stroke (s_min..s_max)";
    case TSE_ALPHA:
        return "a scissor would pass its angle stop (alpha_min..alpha_max)";
    case TSE_SINGULAR:
        return "it comes within the type-1 singularity margin (mu_min)";
    case TSE_DEGENERATE:
        return "it comes within the type-2 singularity margin (nu_min)";
    case TSE_BELOW:
        return "a ball joint would be at or below the base";
    case TSE_UNREACHABLE:
        return "the pose cannot be reached";
    default:
        return "the inverse kinematics fails there";
    }
}

static const char *where(const plan_waypoint *wp, int i, char *buf, size_t cap)
{
    const int number = wp[i].number > 0 ? wp[i].number : i + 1;
    if (wp[i].number < 0)
        snprintf(buf, cap, "the plate's pose (where the path starts)");
    else if (wp[i].line > 0)
        snprintf(buf, cap, "waypoint %d (line %d)", number, wp[i].line);
    else
        snprintf(buf, cap, "waypoint %d", number);
    return buf;
}

const char *plan_explain(const plan_result *r, const plan_waypoint *wp, char *buf, size_t cap)
{
    char a[64], b[64];
    switch (r->status) {
    case PLAN_OK:
        snprintf(buf, cap, "planned");
        break;
    case PLAN_BAD_INPUT:
        if (r->waypoint >= 0)
            snprintf(buf, cap, "%s: %s", where(wp, r->waypoint, a, sizeof a), r->why);
        else if (r->period_min > 0.0)
            snprintf(buf, cap, "rows closer than %.4g s apart: the controller's queue of %d rows would hold less path "
                               "than a stop from the slides' speed limit needs (an underrun); use --period %.4g or more",
                     r->period_min, FW_TRAJ_CAPACITY, r->period_min);
        else
            snprintf(buf, cap, "%s", r->why);
        break;
    case PLAN_PARAMS:
        snprintf(buf, cap, "the controller would refuse the parameter set itself (at its rates)");
        break;
    case PLAN_WORKSPACE:
        if (r->between)
            snprintf(buf, cap, "the path from %s to %s leaves the workspace %.0f %% of the way: %s (%s, scissor %d)",
                     where(wp, r->waypoint, a, sizeof a), where(wp, r->waypoint + 1, b, sizeof b), 100.0 * r->at,
                     kin_words(r->kin), tse_status_name(r->kin), r->scissor);
        else
            snprintf(buf, cap, "%s is outside the workspace: %s (%s, scissor %d)", where(wp, r->waypoint, a, sizeof a),
                     kin_words(r->kin), tse_status_name(r->kin), r->scissor);
        break;
    case PLAN_TIME:
        if (isnan(r->t_needed))
            snprintf(buf, cap, "%s: t = %.6g s cannot be kept together with the other waypoints' times",
                     where(wp, r->waypoint, a, sizeof a), wp[r->waypoint].t);
        else
            snprintf(buf, cap, "%s: t = %.6g s cannot be kept: the slides' limits need until t = %.6g s",
                     where(wp, r->waypoint, a, sizeof a), wp[r->waypoint].t, r->t_needed);
        break;
    case PLAN_TOO_LONG:
        snprintf(buf, cap, "the path is too long to plan (more than %ld grid points of %.4g m) or the memory given "
                           "is short", PLAN_GRID_MAX, PLAN_GRID_STEP);
        break;
    case PLAN_REFUSED:
        snprintf(buf, cap, "the controller's validator still refuses row %ld after %d retries", r->row + 1, r->retries);
        break;
    }
    return buf;
}
