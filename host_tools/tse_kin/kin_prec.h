/* Private to the two files compiled once per precision (kin_ops.c, kin_bench.c).
 *
 * Promise: KIN_PREC gives every symbol they export a _double or _float suffix, so both copies link
 * into one program; kin_ctx is the same layout for both within one copy. */
#ifndef TSE_KIN_PREC_H
#define TSE_KIN_PREC_H

#include "kin_ops.h"
#include "tse/geometry.h"

#if defined(TSE_REAL_FLOAT) && TSE_REAL_FLOAT
#define KIN_PREC(name) name##_float
#else
#define KIN_PREC(name) name##_double
#endif

struct kin_ctx {
    tse_params params; /* kept for tse_haf, which builds its own k1 = 1 geometry */
    tse_geometry g;
};

#define kin_bench_run KIN_PREC(kin_bench_run)

/* The timing loops of kin_ops.bench (kin_bench.c). */
int kin_bench_run(const kin_ctx *c, const double (*poses)[6], int n, int repeats, kin_bench_result *out);

#endif
