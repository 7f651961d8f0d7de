/* What every host benchmark times with: a monotonic clock in nanoseconds and the median of a
 * batch of timings (this VM's clock drifts, so figures are medians of rounds, never single runs).
 * The includer defines _POSIX_C_SOURCE (clock_gettime) before its first system header. */
#ifndef TSE_BENCH_CLOCK_H
#define TSE_BENCH_CLOCK_H

#include <stdlib.h>
#include <time.h>

static inline double bench_now_ns(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec * 1e9 + (double)t.tv_nsec;
}

static inline int bench_cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Sorts v in place; the mean of the middle two for an even n. */
static inline double bench_median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, bench_cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

#endif
