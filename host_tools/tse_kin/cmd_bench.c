/* `tse-kin bench`: how fast the library is, in both precisions, on a path a controller would follow.
 *
 * Promise: labelled lines for people and `bench,KEY,VALUE` lines for scripts (bench/fsolve_baseline.py
 * reads bench,ik_double_warm_ns and bench,ik_double_cold_ns).  The trajectory is the one
 * bench/fsolve_baseline.py defines, so the two tools time the same poses. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "commands.h"

/* Batches per figure; odd, so the median is one batch's mean. */
enum { BENCH_REPEATS = 31 };

const char cmd_bench_help[] =
    "usage: tse-kin bench [--params|--design FILE] [--n N]\n"
    "       tse-kin bench plan [--params FILE]\n"
    "\n"
    "bench plan: plans a path of 1,000 waypoints (the planner of tse-kin plan) and validates the\n"
    "result as tsectl checks a file before sending it; prints both times (medians of 5 rounds), their\n"
    "ratio and bench,plan_ms / validate_ms / plan_over_validate / plan_rows / plan_retries lines.\n"
    "Otherwise:\n"
    "\n"
    "Times the library, double then float, on N poses (default 2000) of a smooth path through the\n"
    "workspace: pose k at t = 0.002 k, X = 0.15 sin t, Y = 0.12 sin 1.7t, Z = 1 + 0.3 sin 0.5t,\n"
    "roll = 0.08 sin 1.3t, pitch = 0.06 sin 0.9t, yaw = 0.2 sin 0.7t (steps below a millimetre and a\n"
    "milliradian, as a control loop takes them). Each figure is the median over 31 batches of the\n"
    "batch's mean time per call, timed with CLOCK_MONOTONIC around the whole batch:\n"
    "  ik PREC cold: 6-DOF inverse kinematics from home (no seed)\n"
    "  ik PREC warm: seeded with the previous pose's solution\n"
    "  fk PREC warm: forward kinematics of each pose's slides, seeded with the previous pose\n"
    "with Newton iterations per pose (mean, max; summed over the three scissors for ik) and the\n"
    "number of scissor solves that needed the quartic fallback. Machine-readable lines:\n"
    "  bench,KEY,VALUE  with KEY ik_PREC_cold_ns, ik_PREC_warm_ns, fk_PREC_ns,\n"
    "  ik_PREC_{cold,warm}_iter_mean, ik_PREC_{cold,warm}_iter_max, ik_PREC_{cold,warm}_fallbacks,\n"
    "  fk_PREC_iter_mean, fk_PREC_iter_max, PREC_not_ok  (PREC double or float)\n"
    "\n" KIN_HELP_PARAMS "\n" KIN_HELP_EXIT;

static void trajectory(double (*p)[6], long n)
{
    for (long i = 0; i < n; ++i) {
        const double t = 0.002 * (double)i;
        p[i][0] = 0.15 * sin(t);
        p[i][1] = 0.12 * sin(1.7 * t);
        p[i][2] = 1.0 + 0.3 * sin(0.5 * t);
        p[i][3] = 0.08 * sin(1.3 * t);
        p[i][4] = 0.06 * sin(0.9 * t);
        p[i][5] = 0.2 * sin(0.7 * t);
    }
}

static void print_result(const char *nm, const kin_bench_result *r)
{
    printf("ik %s cold: median %.1f ns/pose, iterations mean %.2f max %d (3 scissors), fallbacks %ld\n", nm, r->ik_cold_ns,
           r->iter_cold_mean, r->iter_cold_max, r->fallbacks_cold);
    printf("ik %s warm: median %.1f ns/pose, iterations mean %.2f max %d (3 scissors), fallbacks %ld\n", nm, r->ik_warm_ns,
           r->iter_warm_mean, r->iter_warm_max, r->fallbacks_warm);
    printf("fk %s warm: median %.1f ns/pose, iterations mean %.2f max %d\n", nm, r->fk_ns, r->iter_fk_mean,
           r->iter_fk_max);
    if (r->not_ok_ik || r->not_ok_fk)
        printf("# warning (%s): %ld poses of the path not ok in ik, %ld in fk: the figures include failures\n", nm,
               r->not_ok_ik, r->not_ok_fk);
    printf("bench,ik_%s_cold_ns,%.1f\n", nm, r->ik_cold_ns);
    printf("bench,ik_%s_warm_ns,%.1f\n", nm, r->ik_warm_ns);
    printf("bench,fk_%s_ns,%.1f\n", nm, r->fk_ns);
    printf("bench,ik_%s_cold_iter_mean,%.3f\n", nm, r->iter_cold_mean);
    printf("bench,ik_%s_cold_iter_max,%d\n", nm, r->iter_cold_max);
    printf("bench,ik_%s_cold_fallbacks,%ld\n", nm, r->fallbacks_cold);
    printf("bench,ik_%s_warm_iter_mean,%.3f\n", nm, r->iter_warm_mean);
    printf("bench,ik_%s_warm_iter_max,%d\n", nm, r->iter_warm_max);
    printf("bench,ik_%s_warm_fallbacks,%ld\n", nm, r->fallbacks_warm);
    printf("bench,fk_%s_iter_mean,%.3f\n", nm, r->iter_fk_mean);
    printf("bench,fk_%s_iter_max,%d\n", nm, r->iter_fk_max);
    printf("bench,%s_not_ok,%ld\n", nm, r->not_ok_ik + r->not_ok_fk);
}

int cmd_bench(const kin_run *run)
{
    if (run->opt->n_args == 1)
        return cmd_bench_plan(run);
    /* Both designs first: a set that only float rejects must fail before anything is timed. */
    const kin_ops *const all[2] = {&kin_ops_double, &kin_ops_float};
    kin_ctx *ctx[2] = {NULL, NULL};
    for (int k = 0; k < 2; ++k) {
        tse_param_id bad;
        ctx[k] = all[k]->create(run->params, &bad);
        if (!ctx[k]) {
            char err[512], note[64];
            snprintf(note, sizeof note, " in %s precision", all[k]->name);
            kin_params_describe_invalid(run->params, bad, run->params_name, note, err, sizeof err);
            fprintf(stderr, "tse-kin: %s\n", err);
            if (k == 1)
                all[0]->destroy(ctx[0]);
            return KIN_EXIT_FILE;
        }
    }
    const long n = run->opt->bench_n;
    double(*poses)[6] = malloc(sizeof(double[6]) * (size_t)n);
    int rc = KIN_EXIT_OK;
    if (!poses) {
        fprintf(stderr, "tse-kin: out of memory for %ld poses\n", n);
        rc = KIN_EXIT_FILE;
    } else {
        trajectory(poses, n);
        printf("# %ld poses per batch, %d batches, median of the batch means\n", n, BENCH_REPEATS);
        printf("# iterations: Newton steps per pose (ik: summed over the 3 scissors); fallbacks: scissor solves "
               "that needed the quartic\n");
    }
    for (int k = 0; k < 2 && rc == KIN_EXIT_OK; ++k) {
        kin_bench_result r;
        if (all[k]->bench(ctx[k], (const double(*)[6])poses, (int)n, BENCH_REPEATS, &r) != 0) {
            fprintf(stderr, "tse-kin: out of memory for the %s bench\n", all[k]->name);
            rc = KIN_EXIT_FILE;
            break;
        }
        print_result(all[k]->name, &r);
        fflush(stdout); /* the double figures show while the float ones are measured */
    }
    for (int k = 0; k < 2; ++k)
        all[k]->destroy(ctx[k]);
    free(poses);
    if (ferror(stdout)) {
        fprintf(stderr, "tse-kin: error writing the output\n");
        return KIN_EXIT_FILE;
    }
    return rc;
}
