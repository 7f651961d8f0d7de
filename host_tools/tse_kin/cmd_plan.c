/* `tse-kin plan`: a waypoint file to the rows of a trajectory the controller accepts, near the
 * fastest its slides allow (planner/include/plan/plan.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "commands.h"
#include "controller_set.h"
#include "fw/limits.h"
#include "plan_text.h"
#include "waypoint_file.h"

_Static_assert(FW_STEP_HZ == 200000u && FW_SEGMENT_HZ == 1000u, "the help below says the built-in rates");

const char cmd_plan_help[] =
    "usage: tse-kin plan [--params FILE] [--blend M] [--period S] [--jerk J|controller] WAYPOINTS.csv\n"
    "\n"
    "Plans a path through the waypoints and the fastest time law along it that the controller's\n"
    "slides allow, and writes it as a trajectory file (t,x,y,z,roll,pitch,yaw; tsectl trajectory\n"
    "sends it) on stdout: a header, '#' lines saying what was planned, then rows --period apart\n"
    "(default 0.02 s) plus one where each waypoint is passed. The first row holds the first waypoint\n"
    "traj_lead (0.2 s) after the start: the controller accepts the rows from rest there, and starts\n"
    "the motion once the host has queued enough path. Rows are never closer than the controller's\n"
    "queue of 32 rows allows at the slides' speed limit (2.27 v / slide_amax of path for a stop;\n"
    "0.0118 s with the defaults): a shorter --period is refused naming the least.\n"
    "\n"
    "The path goes through every waypoint on a smooth curve (a cubic spline in the six pose\n"
    "coordinates), or with --blend M along straight pieces whose corners it cuts by at most M metres\n"
    "(rotations count as the plate's ball joints move, r_top times the angle). The time law holds\n"
    "every slide within the controller's speed limit (slide_vmax, or the step generator's bound) and\n"
    "acceleration limit (0.95 of slide_amax, as its validator measures rows: more than 0.01 s apart,\n"
    "each row may change a slide's speed by 0.95 slide_amax x 0.01 s). The rows are checked by the\n"
    "controller's own validator before anything is written. The limits are those of a controller at\n"
    "the built-in rates (200 kHz step interrupts, 1 kHz control segments; tsectl path plans at the\n"
    "rates a controller reports in INFO).\n"
    "\n"
    "The controller bounds no trajectory's jerk (its rows are straight: each changes the speed at once,\n"
    "and the validator judges acceleration over 0.01 s). --jerk J holds each slide's jerk along the\n"
    "planned motion to J m/s^3 as well ('controller': the limit the controller's own moves keep to,\n"
    "slide_amax x plate_jmax / plate_amax, 10 m/s^3 with the defaults): the time law is smoothed over a\n"
    "window of slide_amax / J or a little more, and the motion takes about that much longer.\n"
    "\n"
    "WAYPOINTS.csv: rows x,y,z,roll,pitch,yaw (metres, radians); '#' comments and blank lines\n"
    "skipped. A header line may name the columns in any order and add t (the time the waypoint is\n"
    "passed, seconds from the start; empty where free) and v (the plate's speed from that waypoint\n"
    "on at most, m/s; empty where none). A bad row is refused as FILE:LINE naming the column.\n"
    "\n"
    "--params FILE: the controller's parameter file (as tse-sim and 'tsectl params dump' write it):\n"
    "the geometry and the motion limits; default: the controller's defaults.\n"
    "\n"
    "Exit status: 0 planned, 1 unreadable or invalid file, 2 usage error, 3 refused (a waypoint or\n"
    "the path between two outside the workspace, a time that cannot be kept; named on stderr);\n"
    "nothing is written on stdout unless planned.\n";

int cmd_plan(const kin_run *run)
{
    const char *path = run->opt->args[0];
    fw_param_set set;
    int rc = kin_controller_set(run, &set);
    if (rc != KIN_EXIT_OK)
        return rc;
    waypoint_row *rows;
    char err[768];
    const int n = waypoint_file_read(path, &rows, err, sizeof err);
    if (n < 0) {
        fprintf(stderr, "tse-kin: %s\n", err);
        return KIN_EXIT_FILE;
    }
    plan_options o;
    plan_options_default(&o);
    o.blend = run->opt->blend;
    if (run->opt->period > 0.0)
        o.period = run->opt->period;
    o.jmax = run->opt->jerk;
    plan_waypoint *wp = malloc((size_t)n * sizeof *wp);
    plan_made made = {NULL, NULL};
    if (!wp) {
        fprintf(stderr, "tse-kin: out of memory\n");
        free(rows);
        return KIN_EXIT_FILE;
    }
    plan_waypoints_from_rows(rows, n, wp);
    free(rows);
    if (plan_text_make(&set, wp, n, &o, path, &made, err, sizeof err) != 0) {
        fprintf(stderr, "tse-kin: %s\n", err);
        rc = KIN_EXIT_REFUSED;
    } else {
        plan_stats st;
        plan_measure(made.p, &st);
        printf("# tse-kin plan %s: %d waypoints, %.3f s, %ld rows %.3g s apart", path, n, plan_duration(made.p),
               plan_row_count(made.p), o.period);
        if (o.blend > 0.0)
            printf(", corners cut by at most %g m", o.blend);
        if (st.j_limit > 0.0)
            printf(", slides' jerk within %g m/s^3", st.j_limit);
        printf("; the validator refused %d time%s (a stretch slowed each time)\n", plan_retries(made.p),
               plan_retries(made.p) == 1 ? "" : "s");
        plan_print_stats(stdout, "# ", &st);
        plan_write_rows(stdout, made.p);
        if (fflush(stdout) != 0 || ferror(stdout)) {
            fprintf(stderr, "tse-kin: error writing the output\n");
            rc = KIN_EXIT_FILE;
        }
    }
    free(made.mem);
    free(wp);
    return rc;
}
