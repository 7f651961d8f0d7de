/* Shared helpers of the kinematics tests.  Every test source is compiled twice, with
 * TSE_REAL_FLOAT=0 (links tse_kin_d) and TSE_REAL_FLOAT=1 (links tse_kin_f); the tolerances below
 * follow the precision. */
#ifndef TSE_TEST_COMMON_H
#define TSE_TEST_COMMON_H

#include <float.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "oracle.h"
#include "tse/fk.h"
#include "tse/geometry.h"
#include "tse/ik.h"
#include "tse/jacobian.h"
#include "tse/metrics.h"
#include "tse/params.h"
#include "tse/status.h"

#if TSE_REAL_FLOAT
#define IS_FLOAT 1
/* kinematics.md: accepted poses within 2e-6 m of the exact slides in single precision (mu >= 0.1) */
#define TOL_Q 2e-6
/* comparing two float results that should agree (each within TOL_Q of the truth) */
#define TOL_Q2 4e-6
/* 14-digit worked values */
#define TOL_WORKED 2e-6
#else
#define IS_FLOAT 0
#define TOL_Q 1e-9
#define TOL_Q2 2e-9
#define TOL_WORKED 1e-10 /* the solver stops at an estimated 2.6e-12 m (kinematics/src/scissor_core.h): the
                          * worked values' last digits are not its promise, 1e-9 m is; 1e-10 still
                          * catches any lost nanometre */
#endif

/* Widths of the "too close to call" band around each threshold for the oracle's classification:
 * several times the error the contract allows on the quantity in this precision. */
static inline orc_tol test_orc_tol(void)
{
    orc_tol t;
#if TSE_REAL_FLOAT
    t.len = 2e-5L;
    t.ang = 2e-4L;
    t.mu = 2e-4L;
    t.mu_noise = 8.0L * FLT_EPSILON;
    t.nu = 2e-5L;
#else
    t.len = 1e-8L;
    t.ang = 1e-7L;
    t.mu = 1e-7L;
    t.mu_noise = 8.0L * DBL_EPSILON;
    t.nu = 1e-9L;
#endif
    return t;
}

/* splitmix64: a fixed, portable sequence */
static inline uint64_t rng_next(uint64_t *s)
{
    uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

static inline double rng_unit(uint64_t *s)
{
    return (double)(rng_next(s) >> 11) * (1.0 / 9007199254740992.0);
}

static inline double rng_range(uint64_t *s, double lo, double hi)
{
    return lo + (hi - lo) * rng_unit(s);
}

/* The other designs the oracle tests sweep (test_oracle.c, test_ik_fixed.c): the prototype with
 * k1, eta, k3 and k4 drawn from seed, the sixth (d = 5) with its slides pointing inwards. */
static inline void test_other_design(uint64_t *seed, int d, tse_params *p)
{
    tse_params_default(p);
    p->k1 = (tse_real)rng_range(seed, 0.2, 0.6);
    p->eta = (tse_real)rng_range(seed, 0.2, 0.9);
    p->k3 = (tse_real)rng_range(seed, 0.0, 0.05);
    p->k4 = (tse_real)rng_range(seed, 0.08, 0.2);
    if (d == 5)
        p->eta = (tse_real)-0.4;
}

static inline orc_params test_orc_params(const tse_params *p)
{
    orc_params o;
    o.L = (orc_real)p->L;
    o.k1 = (orc_real)p->k1;
    o.eta = (orc_real)p->eta;
    o.k3 = (orc_real)p->k3;
    o.k4 = (orc_real)p->k4;
    o.alpha_min = (orc_real)p->alpha_min;
    o.alpha_max = (orc_real)p->alpha_max;
    o.s_min = (orc_real)p->s_min;
    o.s_max = (orc_real)p->s_max;
    o.mu_min = (orc_real)p->mu_min;
    o.nu_min = (orc_real)p->nu_min;
    return o;
}

/* Geometry of the library and of the oracle from the same (possibly modified) parameters. */
static inline void test_geometries(const tse_params *p, tse_geometry *g, orc_geom *og)
{
    tse_param_id id = tse_geometry_init(g, p);
    assert_int_equal(id, TSE_PARAM_OK);
    orc_params op = test_orc_params(p);
    orc_geom_init(og, &op);
}

static inline void test_default_geometries(tse_geometry *g, orc_geom *og)
{
    tse_params p;
    tse_params_default(&p);
    test_geometries(&p, g, og);
}

static inline void pose_to_orc(const tse_real pose[6], orc_real out[6])
{
    for (int k = 0; k < 6; k++)
        out[k] = (orc_real)pose[k];
}

static inline void q_to_orc(const tse_real q[6], orc_real out[6])
{
    for (int k = 0; k < 6; k++)
        out[k] = (orc_real)q[k];
}

static inline void set_pose(tse_real pose[6], double x, double y, double z, double roll,
                            double pitch, double yaw)
{
    pose[0] = (tse_real)x;
    pose[1] = (tse_real)y;
    pose[2] = (tse_real)z;
    pose[3] = (tse_real)roll;
    pose[4] = (tse_real)pitch;
    pose[5] = (tse_real)yaw;
}

static inline int all_finite_q(const tse_real q[6])
{
    for (int k = 0; k < 6; k++)
        if (!isfinite(q[k]))
            return 0;
    return 1;
}

static inline const char *st_name(int s)
{
    const char *n = tse_status_name((tse_status)s);
    return n ? n : "(null)";
}

#define POSE_FMT "(%.17g, %.17g, %.17g, %.17g, %.17g, %.17g)"
#define POSE_ARGS(p)                                                                             \
    (double)(p)[0], (double)(p)[1], (double)(p)[2], (double)(p)[3], (double)(p)[4], (double)(p)[5]

/* |a - b| <= tol, with a message naming the expression and both values */
#define EXPECT_NEAR(a, b, tol)                                                                   \
    do {                                                                                         \
        double a_ = (double)(a), b_ = (double)(b), t_ = (double)(tol);                           \
        if (!(fabs(a_ - b_) <= t_)) {                                                            \
            print_error("%s:%d: %s = %.17g, expected %s = %.17g (|diff| %.3g > tol %.3g)\n",     \
                        __FILE__, __LINE__, #a, a_, #b, b_, fabs(a_ - b_), t_);                  \
            fail();                                                                              \
        }                                                                                        \
    } while (0)

#define EXPECT_STATUS(got, want)                                                                 \
    do {                                                                                         \
        int g_ = (int)(got), w_ = (int)(want);                                                   \
        if (g_ != w_) {                                                                          \
            print_error("%s:%d: status %s (%d), expected %s (%d)\n", __FILE__, __LINE__,         \
                        st_name(g_), g_, st_name(w_), w_);                                       \
            fail();                                                                              \
        }                                                                                        \
    } while (0)

#endif
