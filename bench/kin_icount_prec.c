/* kin-icount's measured loops, compiled once per precision (see kin_icount.h).  Every name below
 * gets _double_ or _float_ in it through ICOUNT_PREC. */
#include <stdlib.h>
#include <string.h>

#include "kin_icount.h"
#include "kin_icount_stub.h"
#include "tse/params.h"

#define kin_icount_setup ICOUNT_PREC(kin_icount, setup)
#define measure_ik_warm ICOUNT_PREC(measure_ik, warm)
#define measure_loop_ik_warm ICOUNT_PREC(measure_loop_ik, warm)
#define measure_ik_cold ICOUNT_PREC(measure_ik, cold)
#define measure_loop_ik_cold ICOUNT_PREC(measure_loop_ik, cold)
#define measure_fk_warm ICOUNT_PREC(measure_fk, warm)
#define measure_loop_fk_warm ICOUNT_PREC(measure_loop_fk, warm)

#define NOINLINE __attribute__((noinline))
#define ALWAYS_INLINE inline __attribute__((always_inline))

typedef tse_status (*ik_fn)(const tse_geometry *, const tse_real[6], const tse_real[6], tse_ik_result *);
typedef tse_status (*fk_fn)(const tse_geometry *, const tse_real[6], const tse_real[6], tse_fk_result *);

/* Filled by the set-up, read by the measures. */
static struct {
    tse_geometry g;
    tse_real (*p)[6]; /* the path */
    tse_real (*q)[6]; /* its warm inverse kinematics */
    int n;
    tse_real first_seed[6];
} st;

/* Every loop stores a sum of its results here: the work has an observable effect. */
static volatile double icount_sink;

/* The loops, each written once and inlined with the library function or the stub, so that the
 * real and the overhead measures run the same code around the call. */
static ALWAYS_INLINE void ik_warm_loop(ik_fn ik)
{
    tse_real seed[6], acc = TSE_R(0.0);
    memcpy(seed, st.first_seed, sizeof seed);
    tse_ik_result r = {.status = TSE_OK};
    for (int i = 0; i < st.n; ++i) {
        if (ik(&st.g, st.p[i], seed, &r) == TSE_OK)
            memcpy(seed, r.q, sizeof seed);
        acc += r.q[0];
    }
    icount_sink = (double)acc;
}

static ALWAYS_INLINE void ik_cold_loop(ik_fn ik)
{
    tse_real acc = TSE_R(0.0);
    tse_ik_result r = {.status = TSE_OK};
    for (int i = 0; i < st.n; ++i) {
        ik(&st.g, st.p[i], NULL, &r);
        acc += r.q[0];
    }
    icount_sink = (double)acc;
}

static ALWAYS_INLINE void fk_warm_loop(fk_fn fk)
{
    tse_real acc = TSE_R(0.0);
    tse_fk_result f = {.status = TSE_OK};
    for (int i = 1; i < st.n; ++i) {
        fk(&st.g, st.q[i], st.p[i - 1], &f);
        acc += f.pose[0];
    }
    icount_sink = (double)acc;
}

NOINLINE void measure_ik_warm(void) { ik_warm_loop(tse_ik); }
NOINLINE void measure_loop_ik_warm(void) { ik_warm_loop(icount_stub_ik); }
NOINLINE void measure_ik_cold(void) { ik_cold_loop(tse_ik); }
NOINLINE void measure_loop_ik_cold(void) { ik_cold_loop(icount_stub_ik); }
NOINLINE void measure_fk_warm(void) { fk_warm_loop(tse_fk); }
NOINLINE void measure_loop_fk_warm(void) { fk_warm_loop(icount_stub_fk); }

int kin_icount_setup(const double (*poses)[6], int n)
{
    tse_params prm;
    tse_params_default(&prm);
    if (n < 2 || tse_geometry_init(&st.g, &prm) != TSE_PARAM_OK)
        return -1;
    st.p = malloc(sizeof(tse_real[6]) * (size_t)n);
    st.q = malloc(sizeof(tse_real[6]) * (size_t)n);
    if (!st.p || !st.q)
        return -1;
    st.n = n;
    for (int i = 0; i < n; ++i)
        for (int k = 0; k < 6; ++k)
            st.p[i][k] = (tse_real)poses[i][k];
    tse_ik_result r;
    tse_ik(&st.g, st.p[0], NULL, &r);
    memcpy(st.first_seed, r.q, sizeof st.first_seed);
    /* The warm solutions, as measure_ik_warm finds them. */
    int rejected = 0;
    tse_real seed[6];
    memcpy(seed, st.first_seed, sizeof seed);
    for (int i = 0; i < n; ++i) {
        if (tse_ik(&st.g, st.p[i], seed, &r) == TSE_OK)
            memcpy(seed, r.q, sizeof seed);
        else
            ++rejected;
        memcpy(st.q[i], r.q, sizeof seed);
    }
    tse_fk_result f;
    if (tse_fk(&st.g, st.q[1], st.p[0], &f) != TSE_OK)
        ++rejected;
    return rejected;
}
