/* path WAYPOINTS.csv: a path planned through waypoints against the controller's own parameters
 * and rates and from where it is (the planner of tse-kin plan), then streamed as `trajectory` streams a file
 * (checked whole first; STOP on a refusal or Ctrl-C).  --dry-run plans and prints, sending nothing;
 * --plot FILE.png draws the plan first (path_plot.h). */
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "path_plot.h"
#include "plan_text.h"
#include "text.h"
#include "traj_send.h"

typedef struct {
    const char *path;
    const char *png; /* --plot */
    bool dry_run;
    plan_options o;
} path_args;

/* Within this of the plate's pose, the first waypoint is where it is [m, rad]. */
#define PATH_AT_START 10e-6
#define PATH_PI 3.14159265358979323846

static int parse(int argc, char **argv, path_args *a)
{
    memset(a, 0, sizeof *a);
    plan_options_default(&a->o);
    for (int i = 0; i < argc; ++i) {
        const char *s = argv[i];
        double *value = !strcmp(s, "--blend") ? &a->o.blend : !strcmp(s, "--period") ? &a->o.period : NULL;
        if (!strcmp(s, "--dry-run")) {
            a->dry_run = true;
        } else if (!strcmp(s, "--jerk")) {
            if (i + 1 >= argc)
                return usage_error("path", "a value is missing after", s);
            if (plan_jerk_from_text(argv[i + 1], &a->o.jmax) != 0)
                return usage_error("path", "--jerk takes the slides' jerk limit in m/s^3 above 0 and up to 1e6, or "
                                           "'controller'", argv[i + 1]);
            ++i;
        } else if (!strcmp(s, "--plot")) {
            if (i + 1 >= argc || !argv[i + 1][0])
                return usage_error("path", "--plot needs a FILE.png", NULL);
            a->png = argv[++i];
        } else if (value) {
            if (i + 1 >= argc || text_number(argv[i + 1], value) != 0)
                return usage_error("path", i + 1 < argc ? "a number of metres (--blend) or seconds (--period) expected"
                                                        : "a value is missing after", i + 1 < argc ? argv[i + 1] : s);
            if (value == &a->o.blend && !(*value >= 0.0 && *value <= PLAN_BLEND_MAX))
                return usage_error("path", "--blend takes 0 to 1 m", argv[i + 1]);
            if (value == &a->o.period && !(*value >= PLAN_PERIOD_MIN && *value <= PLAN_PERIOD_MAX))
                return usage_error("path", "--period takes 0.001 to 1 s", argv[i + 1]);
            ++i;
        } else if (s[0] == '-' && s[1] == '-') {
            return usage_error("path", "unknown option", s);
        } else if (a->path) {
            return usage_error("path", "takes one FILE", s);
        } else {
            a->path = s;
        }
    }
    if (!a->path)
        return usage_error("path", "needs a waypoint FILE", NULL);
    return EXIT_OK;
}

int check_path(int argc, char **argv, int *done)
{
    (void)done;
    path_args a;
    const int rc = parse(argc, argv, &a);
    if (rc != EXIT_OK)
        return rc;
    waypoint_row *rows;
    char err[512];
    if (waypoint_file_read(a.path, &rows, err, sizeof err) < 0) {
        ctl_error("%s", err);
        return EXIT_USAGE;
    }
    free(rows);
    if (a.png && path_plot_available(err, sizeof err) != 0) {
        ctl_error("%s", err);
        return EXIT_USAGE;
    }
    return EXIT_OK;
}

/* The waypoints planned: from the plate's pose.  When the file's first waypoint is there already
 * it becomes the start; otherwise the path goes to it first (and its t, if 0, is no longer the
 * start's).  Returns the index in wp of the first waypoint planned. */
static int from_here(const waypoint_row *rows, int n, const double here[6], plan_waypoint *wp)
{
    plan_waypoints_from_rows(rows, n, wp + 1);
    double d = 0.0;
    for (int k = 0; k < 6; ++k)
        d = fmax(d, fabs(k < 3 ? here[k] - rows[0].pose[k] : remainder(here[k] - rows[0].pose[k], 2.0 * PATH_PI)));
    if (d <= PATH_AT_START) {
        memcpy(wp[1].pose, here, sizeof wp[1].pose);
        wp[1].t = NAN;
        return 1;
    }
    wp[0] = (plan_waypoint){{here[0], here[1], here[2], here[3], here[4], here[5]}, NAN, NAN, 0, -1};
    if (wp[1].t == 0.0)
        wp[1].t = NAN;
    return 0;
}

int run_path(tlink *l, int argc, char **argv)
{
    path_args a;
    parse(argc, argv, &a);
    waypoint_row *rows;
    char err[768];
    const int n = waypoint_file_read(a.path, &rows, err, sizeof err);
    if (n < 0) {
        ctl_error("%s", err);
        return EXIT_USAGE;
    }
    traj_session s;
    plan_waypoint *wp = malloc((size_t)(n + 1) * sizeof *wp);
    plan_made m = {NULL, NULL};
    traj_row *out = NULL;
    int rc = wp ? traj_prepare(l, !a.dry_run, &s) : EXIT_BUS;
    if (!wp) {
        ctl_error("out of memory");
    } else if (rc != EXIT_OK) {
        /* reported */
    } else if (!s.have_start) {
        ctl_error("no telemetry from node %u (telemetry_ms is 0?): a path is planned from where the plate is",
                  l->node);
        rc = EXIT_REJECTED;
    } else {
        const int skip = from_here(rows, n, s.tel.pose, wp);
        const plan_waypoint *first = wp + skip;
        const int count = n + 1 - skip;
        a.o.rates = s.rates;
        if (plan_text_make(&s.set, first, count, &a.o, a.path, &m, err, sizeof err) != 0) {
            ctl_error("%s; nothing was sent", err);
            rc = EXIT_REJECTED;
        } else if (a.png && path_plot(m.p, &s.set, s.rates, a.png, err, sizeof err) != 0) {
            ctl_error("%s; nothing was sent", err);
            rc = EXIT_USAGE;
        } else if (a.dry_run) {
            plan_stats st;
            plan_measure(m.p, &st);
            printf("# %s planned from node %u's pose and parameters at its %u Hz step interrupts and %u Hz control "
                   "segments: %.3f s, %ld rows\n",
                   a.path, l->node, s.rates.step_hz, s.rates.segment_hz, plan_duration(m.p), plan_row_count(m.p));
            plan_print_stats(stdout, "# ", &st);
            plan_write_rows(stdout, m.p);
        } else if (!(out = malloc((size_t)plan_row_count(m.p) * sizeof *out))) {
            ctl_error("out of memory");
            rc = EXIT_BUS;
        } else {
            plan_cursor c;
            plan_row row;
            long k = 0;
            for (plan_rows_begin(m.p, &c); plan_rows_next(m.p, &c, &row); ++k) {
                out[k].t = row.t;
                memcpy(out[k].p, row.pose, sizeof out[k].p);
                out[k].line = first[plan_row_waypoint(m.p, row.t)].line;
            }
            printf("%s: planned %.3f s through %d waypoints from where the plate is\n", a.path, plan_duration(m.p), n);
            rc = traj_send(l, &s, a.path, out, (int)k);
        }
    }
    free(out);
    free(m.mem);
    free(wp);
    free(rows);
    return rc;
}
