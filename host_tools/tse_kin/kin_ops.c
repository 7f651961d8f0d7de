/* Compiled twice, with TSE_REAL_FLOAT 0 and 1: see kin_ops.h. */
#define _POSIX_C_SOURCE 200809L
#include "kin_ops.h"

#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "tse/fk.h"
#include "tse/ik.h"
#include "tse/jacobian.h"
#include "tse/metrics.h"

#if defined(TSE_REAL_FLOAT) && TSE_REAL_FLOAT
#define OPS kin_ops_float
#define P(name) name##_float
#else
#define OPS kin_ops_double
#define P(name) name##_double
#endif

struct kin_ctx {
    tse_params params;
    tse_geometry g;
};

static kin_ctx *P(create)(const kin_param_values *p)
{
    kin_ctx *c = calloc(1, sizeof *c);
    if (!c)
        return NULL;
    tse_real *dst[TSE_PARAM_COUNT] = {
        NULL, &c->params.L, &c->params.k1, &c->params.eta, &c->params.k3, &c->params.k4,
        &c->params.alpha_min, &c->params.alpha_max, &c->params.s_min, &c->params.s_max,
        &c->params.mu_min, &c->params.nu_min,
    };
    for (int i = 1; i < TSE_PARAM_COUNT; ++i)
        *dst[i] = (tse_real)p->v[i];
    if (tse_geometry_init(&c->g, &c->params) != TSE_PARAM_OK) {
        free(c);
        return NULL;
    }
    return c;
}

static void P(destroy)(kin_ctx *c)
{
    free(c);
}

static void to_real(const double *in, tse_real *out, int n)
{
    for (int k = 0; k < n; ++k)
        out[k] = (tse_real)in[k];
}

static void to_double(const tse_real *in, double *out, int n)
{
    for (int k = 0; k < n; ++k)
        out[k] = (double)in[k];
}

static int P(ik)(kin_ctx *c, const double pose[6], const double *seed, double q[6], int *scissor,
                 double mu[3], double *nu)
{
    tse_real p[6], s[6];
    to_real(pose, p, 6);
    if (seed)
        to_real(seed, s, 6);
    tse_ik_result r;
    tse_ik(&c->g, p, seed ? s : NULL, &r);
    to_double(r.q, q, 6);
    if (mu)
        to_double(r.mu, mu, 3);
    if (nu)
        *nu = (double)r.nu;
    *scissor = r.scissor;
    return r.status;
}

static int P(fk)(kin_ctx *c, const double q[6], const double *seed, double pose[6], int *scissor)
{
    tse_real qq[6], s[6];
    to_real(q, qq, 6);
    if (seed)
        to_real(seed, s, 6);
    tse_fk_result r;
    tse_fk(&c->g, qq, seed ? s : NULL, &r);
    to_double(r.pose, pose, 6);
    *scissor = r.scissor;
    return r.status;
}

static int P(jacobian)(kin_ctx *c, const double pose[6], double J[36], double sv[6], int *scissor)
{
    tse_real p[6];
    to_real(pose, p, 6);
    tse_ik_result r;
    if (tse_ik(&c->g, p, NULL, &r) != TSE_OK) {
        *scissor = r.scissor;
        return r.status;
    }
    *scissor = 0;
    tse_real Jr[6][6], s[6];
    const tse_status st = tse_jacobian(&c->g, p, r.q, Jr);
    if (st != TSE_OK)
        return st;
    to_double(&Jr[0][0], J, 36);
    tse_singular_values(Jr, s);
    /* dp/dq is the inverse of dq/dp: its singular values are the reciprocals, in reverse. */
    for (int k = 0; k < 6; ++k)
        sv[k] = 1.0 / (double)s[5 - k];
    return TSE_OK;
}

static int P(sigma_z)(kin_ctx *c, double z, double *sigma)
{
    tse_real s;
    const tse_status st = tse_sigma_z(&c->g, (tse_real)z, &s);
    *sigma = (double)s;
    return st;
}

static int P(haf)(kin_ctx *c, double z, double *haf)
{
    tse_real h;
    const tse_status st = tse_haf(&c->params, (tse_real)z, &h);
    *haf = (double)h;
    return st;
}

static int P(workspace)(kin_ctx *c, int nr, int nphi, int nz, const double orient[3], long *reach, long *total)
{
    tse_real o[3];
    to_real(orient, o, 3);
    return tse_workspace(&c->g, nr, nphi, nz, o, reach, total);
}

static double now_ns(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec * 1e9 + (double)t.tv_nsec;
}

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

static void P(bench)(kin_ctx *c, const double (*poses)[6], int n, int repeats, kin_bench_result *out)
{
    tse_real(*p)[6] = malloc(sizeof(tse_real[6]) * (size_t)n);
    tse_real(*q)[6] = malloc(sizeof(tse_real[6]) * (size_t)n);
    double *t_cold = malloc(sizeof(double) * (size_t)repeats);
    double *t_warm = malloc(sizeof(double) * (size_t)repeats);
    double *t_fk = malloc(sizeof(double) * (size_t)repeats);
    memset(out, 0, sizeof *out);
    for (int i = 0; i < n; ++i)
        to_real(poses[i], p[i], 6);
    volatile tse_real sink = 0;
    long it_cold = 0, it_warm = 0;
    for (int r = 0; r < repeats; ++r) {
        tse_ik_result res;
        double t0 = now_ns();
        for (int i = 0; i < n; ++i) {
            tse_ik(&c->g, p[i], NULL, &res);
            sink += res.q[0];
            if (r == 0) {
                it_cold += res.iterations;
                if (res.iterations > out->iter_cold_max)
                    out->iter_cold_max = res.iterations;
                out->fallbacks_cold += res.fallbacks;
            }
        }
        double t1 = now_ns();
        t_cold[r] = (t1 - t0) / n;

        /* Warm: each pose seeded with the solution of the previous one, as a control loop does. */
        tse_ik(&c->g, p[0], NULL, &res);
        tse_real seed[6];
        memcpy(seed, res.q, sizeof seed);
        t0 = now_ns();
        for (int i = 0; i < n; ++i) {
            tse_ik(&c->g, p[i], seed, &res);
            memcpy(seed, res.q, sizeof seed);
            memcpy(q[i], res.q, sizeof seed);
            sink += res.q[0];
            if (r == 0) {
                it_warm += res.iterations;
                if (res.iterations > out->iter_warm_max)
                    out->iter_warm_max = res.iterations;
                out->fallbacks_warm += res.fallbacks;
                if (res.status != TSE_OK)
                    ++out->failures;
            }
        }
        t1 = now_ns();
        t_warm[r] = (t1 - t0) / n;

        /* Forward kinematics of the same trajectory, seeded with the previous pose. */
        t0 = now_ns();
        for (int i = 1; i < n; ++i) {
            tse_fk_result f;
            tse_fk(&c->g, q[i], p[i - 1], &f);
            sink += f.pose[0];
        }
        t1 = now_ns();
        t_fk[r] = (t1 - t0) / (n - 1);
    }
    (void)sink;
    out->ik_cold_ns = median(t_cold, repeats);
    out->ik_warm_ns = median(t_warm, repeats);
    out->fk_ns = median(t_fk, repeats);
    out->iter_cold_mean = (double)it_cold / n;
    out->iter_warm_mean = (double)it_warm / n;
    free(p);
    free(q);
    free(t_cold);
    free(t_warm);
    free(t_fk);
}

const kin_ops OPS = {
    TSE_REAL_NAME, P(create), P(destroy), P(ik), P(fk), P(jacobian), P(sigma_z), P(haf), P(workspace), P(bench),
};
