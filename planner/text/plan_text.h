/* The planner as the host tools use it (tse-kin plan, tsectl path, tse-kin bench plan): waypoint
 * rows in, the plan made in memory of its own, refusals and figures in words, rows out as a
 * trajectory file. */
#ifndef PLAN_TEXT_H
#define PLAN_TEXT_H

#include <stddef.h>
#include <stdio.h>

#include "plan/plan.h"
#include "waypoint_file.h"

typedef struct {
    plan *p;
    void *mem; /* the caller frees it (free(NULL) when planning failed early) */
} plan_made;

void plan_waypoints_from_rows(const waypoint_row *rows, int n, plan_waypoint *wp);

/* Plans wp[0..n) (they must outlive the plan).  Returns 0 with *m, or -1 with "PATH: why" in err
 * (the waypoint and its line, the reason; a validator's refusal in tsectl's words). */
int plan_text_make(const fw_param_set *s, const plan_waypoint *wp, int n, const plan_options *o, const char *path,
                   plan_made *m, char *err, size_t errlen);

/* --jerk's value as tse-kin plan and tsectl path take it: 'controller' (PLAN_JMAX_CONTROLLER) or a
 * limit in m/s^3 above 0 and up to PLAN_JERK_MAX.  Returns 0, or -1 with *jmax untouched. */
int plan_jerk_from_text(const char *text, double *jmax);

/* One line: the peaks against the limits and the share of rows near a limit. */
void plan_print_stats(FILE *f, const char *prefix, const plan_stats *st);

/* The rows as a trajectory file: the header, then t,x,y,z,roll,pitch,yaw rounded as the wire rounds
 * them (micrometres, microradians, microseconds), so that reading them back gives what was checked. */
void plan_write_rows(FILE *f, const plan *p);

#endif
