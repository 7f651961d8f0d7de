/* `tse-kin bench plan`: how long planning a long path takes against validating its result, the
 * check tsectl makes of a file before sending it (issue 25).
 *
 * Promise: labelled lines for people and `bench,KEY,VALUE` lines for scripts; figures are medians
 * over rounds, never asserted. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "bench_clock.h"
#include "commands.h"
#include "controller_set.h"
#include "plan_text.h"
#include "traj_check.h"

enum { PLAN_BENCH_WAYPOINTS = 1000, PLAN_BENCH_ROUNDS = 5 };

/* A wandering loop through the workspace: 10 turns of a 5 cm circle that breathes, rises and falls
 * 8 cm, with the plate tilting and turning; waypoints about 3 mm apart. */
static void bench_waypoints(plan_waypoint *wp, int n)
{
    const double pi = 3.14159265358979323846;
    for (int k = 0; k < n; ++k) {
        const double phi = 2.0 * pi * k / 100.0, r = 0.05 * (1.0 + 0.2 * sin(k / 170.0));
        const double pose[6] = {r * cos(phi) - 0.05, r * sin(phi), 1.0 + 0.08 * sin(2.0 * pi * k / 400.0),
                                0.03 * sin(2.0 * pi * k / 300.0), 0.03 * cos(2.0 * pi * k / 250.0) - 0.03,
                                0.15 * sin(2.0 * pi * k / 500.0)};
        for (int j = 0; j < 6; ++j)
            wp[k].pose[j] = pose[j];
        wp[k].t = wp[k].v = NAN;
        wp[k].line = wp[k].number = 0;
    }
}

int cmd_bench_plan(const kin_run *run)
{
    fw_param_set set;
    int rc = kin_controller_set(run, &set);
    if (rc != KIN_EXIT_OK)
        return rc;
    const int n = PLAN_BENCH_WAYPOINTS;
    plan_waypoint *wp = malloc((size_t)n * sizeof *wp);
    if (!wp)
        return fprintf(stderr, "tse-kin: out of memory\n"), KIN_EXIT_FILE;
    bench_waypoints(wp, n);
    plan_options o;
    plan_options_default(&o);
    double t_plan[PLAN_BENCH_ROUNDS], t_check[PLAN_BENCH_ROUNDS];
    traj_row *rows = NULL;
    long n_rows = 0;
    int retries = 0;
    double duration = 0.0;
    char err[768];
    for (int round = 0; round < PLAN_BENCH_ROUNDS && rc == KIN_EXIT_OK; ++round) {
        plan_made m;
        const double t0 = bench_now_ns();
        if (plan_text_make(&set, wp, n, &o, "bench path", &m, err, sizeof err) != 0) {
            fprintf(stderr, "tse-kin: %s\n", err);
            free(m.mem);
            rc = KIN_EXIT_REFUSED;
            break;
        }
        t_plan[round] = bench_now_ns() - t0;
        n_rows = plan_row_count(m.p);
        retries = plan_retries(m.p);
        duration = plan_duration(m.p);
        free(rows);
        rows = malloc((size_t)n_rows * sizeof *rows);
        if (!rows) {
            free(m.mem);
            rc = KIN_EXIT_FILE;
            break;
        }
        plan_cursor c;
        plan_row row;
        long k = 0;
        for (plan_rows_begin(m.p, &c); plan_rows_next(m.p, &c, &row); ++k) {
            rows[k].t = row.t;
            for (int j = 0; j < 6; ++j)
                rows[k].p[j] = row.pose[j];
            rows[k].line = (int)k + 2;
        }
        double q0[6];
        plan_start_slides(m.p, q0);
        traj_check_result chk;
        const double t1 = bench_now_ns();
        const int verdict = traj_check(&set, o.rates, wp[0].pose, q0, rows, (int)n_rows, &chk);
        t_check[round] = bench_now_ns() - t1;
        free(m.mem);
        if (verdict != 0) {
            fprintf(stderr, "tse-kin: bench path: the validator refuses row %d of the plan\n", chk.row + 1);
            rc = KIN_EXIT_REFUSED;
        }
    }
    if (rc == KIN_EXIT_OK) {
        const double plan_ms = bench_median(t_plan, PLAN_BENCH_ROUNDS) * 1e-6;
        const double check_ms = bench_median(t_check, PLAN_BENCH_ROUNDS) * 1e-6;
        printf("# %d waypoints (a wandering loop, about 3 mm apart), rows %.3g s apart; median of %d rounds\n", n,
               o.period, PLAN_BENCH_ROUNDS);
        printf("plan: %.1f ms for a %.2f s trajectory of %ld rows (the validator refused %d time%s on the way)\n", plan_ms,
               duration, n_rows, retries, retries == 1 ? "" : "s");
        printf("validate: %.1f ms (tsectl's whole-file check of the result)\n", check_ms);
        printf("plan / validate: %.2f\n", plan_ms / check_ms);
        printf("bench,plan_ms,%.3f\nbench,validate_ms,%.3f\nbench,plan_over_validate,%.3f\nbench,plan_rows,%ld\n"
               "bench,plan_retries,%d\n",
               plan_ms, check_ms, plan_ms / check_ms, n_rows, retries);
    }
    free(rows);
    free(wp);
    return rc;
}
