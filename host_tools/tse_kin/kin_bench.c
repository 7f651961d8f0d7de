/* Timing loops of `tse-kin bench`, compiled once per precision so that the timed code calls the
 * library directly, with no conversion to or from double inside the clock.
 *
 * Promise: each figure is the median, over `repeats` batches, of (batch time / poses in the batch),
 * timed with CLOCK_MONOTONIC around whole batches so the clock's own cost is spread over n calls.
 * Iteration counts come from an untimed pass, so that counting does not slow the timed one. */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench_clock.h"
#include "kin_prec.h"
#include "tse/fk.h"
#include "tse/ik.h"

/* Every batch stores a sum of its results here: the work has an observable effect. */
static volatile double bench_sink;

static double time_cold(const tse_geometry *g, tse_real (*p)[6], int n)
{
    tse_real acc = 0;
    tse_ik_result r;
    const double t0 = bench_now_ns();
    for (int i = 0; i < n; ++i) {
        tse_ik(g, p[i], NULL, &r);
        acc += r.q[0];
    }
    const double t1 = bench_now_ns();
    bench_sink = (double)acc;
    return (t1 - t0) / n;
}

/* Seeded with the last good solution, as a controller stepping along the path would be. */
static double time_warm(const tse_geometry *g, tse_real (*p)[6], int n, const tse_real first_seed[6])
{
    tse_real acc = 0, seed[6];
    memcpy(seed, first_seed, sizeof seed);
    tse_ik_result r;
    const double t0 = bench_now_ns();
    for (int i = 0; i < n; ++i) {
        if (tse_ik(g, p[i], seed, &r) == TSE_OK)
            memcpy(seed, r.q, sizeof seed);
        acc += r.q[0];
    }
    const double t1 = bench_now_ns();
    bench_sink = (double)acc;
    return (t1 - t0) / n;
}

/* The slides of pose i, the forward kinematics seeded with pose i - 1. */
static double time_fk(const tse_geometry *g, tse_real (*p)[6], tse_real (*q)[6], int n)
{
    tse_real acc = 0;
    tse_fk_result f;
    const double t0 = bench_now_ns();
    for (int i = 1; i < n; ++i) {
        tse_fk(g, q[i], p[i - 1], &f);
        acc += f.pose[0];
    }
    const double t1 = bench_now_ns();
    bench_sink = (double)acc;
    return (t1 - t0) / (n - 1);
}

/* The untimed pass: iteration statistics, the slides for fk, the warm start's first seed. */
static void count_pass(const tse_geometry *g, tse_real (*p)[6], tse_real (*q)[6], int n, tse_real first_seed[6],
                       kin_bench_result *out)
{
    tse_ik_result r;
    long it_cold = 0, it_warm = 0, it_fk = 0;
    for (int i = 0; i < n; ++i) {
        tse_ik(g, p[i], NULL, &r);
        it_cold += r.iterations;
        out->iter_cold_max = r.iterations > out->iter_cold_max ? r.iterations : out->iter_cold_max;
        out->fallbacks_cold += r.fallbacks;
        if (i == 0)
            memcpy(first_seed, r.q, sizeof(tse_real[6]));
    }
    tse_real seed[6];
    memcpy(seed, first_seed, sizeof seed);
    for (int i = 0; i < n; ++i) {
        if (tse_ik(g, p[i], seed, &r) == TSE_OK)
            memcpy(seed, r.q, sizeof seed);
        else
            ++out->not_ok_ik;
        memcpy(q[i], r.q, sizeof seed);
        it_warm += r.iterations;
        out->iter_warm_max = r.iterations > out->iter_warm_max ? r.iterations : out->iter_warm_max;
        out->fallbacks_warm += r.fallbacks;
    }
    for (int i = 1; i < n; ++i) {
        tse_fk_result f;
        if (tse_fk(g, q[i], p[i - 1], &f) != TSE_OK)
            ++out->not_ok_fk;
        it_fk += f.iterations;
        out->iter_fk_max = f.iterations > out->iter_fk_max ? f.iterations : out->iter_fk_max;
    }
    out->iter_cold_mean = (double)it_cold / n;
    out->iter_warm_mean = (double)it_warm / n;
    out->iter_fk_mean = (double)it_fk / (n - 1);
}

int kin_bench_run(const kin_ctx *c, const double (*poses)[6], int n, int repeats, kin_bench_result *out)
{
    memset(out, 0, sizeof *out);
    if (n < 2 || repeats < 1)
        return -1;
    tse_real(*p)[6] = malloc(sizeof(tse_real[6]) * (size_t)n);
    tse_real(*q)[6] = malloc(sizeof(tse_real[6]) * (size_t)n);
    double *t = malloc(sizeof(double) * 3 * (size_t)repeats);
    if (!p || !q || !t) {
        free(p);
        free(q);
        free(t);
        return -1;
    }
    for (int i = 0; i < n; ++i)
        for (int k = 0; k < 6; ++k)
            p[i][k] = (tse_real)poses[i][k];
    tse_real first_seed[6];
    count_pass(&c->g, p, q, n, first_seed, out);
    double *t_cold = t, *t_warm = t + repeats, *t_fk = t + 2 * (size_t)repeats;
    /* Interleaved, so that a change of clock speed during the run touches all three alike. */
    for (int r = 0; r < repeats; ++r) {
        t_cold[r] = time_cold(&c->g, p, n);
        t_warm[r] = time_warm(&c->g, p, n, first_seed);
        t_fk[r] = time_fk(&c->g, p, q, n);
    }
    out->ik_cold_ns = bench_median(t_cold, repeats);
    out->ik_warm_ns = bench_median(t_warm, repeats);
    out->fk_ns = bench_median(t_fk, repeats);
    free(p);
    free(q);
    free(t);
    return 0;
}
