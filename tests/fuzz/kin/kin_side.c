/* One precision of the library behind doubles (kin_side.h); built once per precision. */
#include "kin_side.h"

#include <float.h>
#include <string.h>

#include "fuzz_target.h"
#include "tse/fk.h"
#include "tse/ik.h"

#define SIDE(name) TSE_NS(name)

static tse_geometry geometry;

/* A double as this precision holds it; beyond float's range an infinity (what IEEE rounding
 * gives), said here so that the conversion is never out of range. */
static tse_real held(double x)
{
    if (sizeof(tse_real) < sizeof(double) && (x > FLT_MAX || x < -FLT_MAX))
        return x > 0 ? (tse_real)INFINITY : -(tse_real)INFINITY;
    return (tse_real)x;
}

static void to_params(const double v[SIDE_NPARAMS], tse_params *p)
{
    tse_real *f[SIDE_NPARAMS] = {&p->L,         &p->k1,        &p->eta,   &p->k3,    &p->k4,     &p->alpha_min,
                                 &p->alpha_max, &p->s_min,     &p->s_max, &p->mu_min, &p->nu_min};
    for (int k = 0; k < SIDE_NPARAMS; ++k)
        *f[k] = held(v[k]);
}

static void from_params(const tse_params *p, double v[SIDE_NPARAMS])
{
    const tse_real f[SIDE_NPARAMS] = {p->L,         p->k1,    p->eta,   p->k3,     p->k4,    p->alpha_min,
                                      p->alpha_max, p->s_min, p->s_max, p->mu_min, p->nu_min};
    for (int k = 0; k < SIDE_NPARAMS; ++k)
        v[k] = (double)f[k];
}

int SIDE(side_init)(const double v[SIDE_NPARAMS], double out[SIDE_NPARAMS])
{
    tse_params p;
    to_params(v, &p);
    from_params(&p, out);
    tse_geometry g;
    memset(&g, 0xA5, sizeof g);
    const tse_geometry untouched = g;
    const tse_param_id bad = tse_geometry_init(&g, &p);
    FUZZ_CHECK(bad == tse_params_check(&p));
    if (bad != TSE_PARAM_OK) {
        FUZZ_CHECK(bad > TSE_PARAM_OK && bad < TSE_PARAM_COUNT);
        FUZZ_CHECK(!memcmp(&g, &untouched, sizeof g));
        return (int)bad;
    }
    geometry = g;
    return TSE_PARAM_OK;
}

void SIDE(side_default)(double v[SIDE_NPARAMS])
{
    tse_params p;
    tse_params_default(&p);
    from_params(&p, v);
}

void SIDE(side_ik)(const double pose[6], const double *seed, side_ik *out)
{
    tse_real p[6], s[6];
    for (int k = 0; k < 6; ++k) {
        p[k] = held(pose[k]);
        s[k] = seed ? held(seed[k]) : 0;
        out->pose[k] = (double)p[k];
        out->seed[k] = (double)s[k];
    }
    tse_ik_result r;
    memset(&r, 0x5A, sizeof r);
    out->ret = (int)tse_ik(&geometry, p, seed ? s : NULL, &r);
    out->status = (int)r.status;
    out->scissor = r.scissor;
    for (int k = 0; k < 6; ++k)
        out->q[k] = (double)r.q[k];
    for (int i = 0; i < 3; ++i)
        out->mu[i] = (double)r.mu[i];
    out->nu = (double)r.nu;
}

void SIDE(side_fk)(const double q[6], const double *seed, side_fk *out)
{
    tse_real qq[6], s[6];
    for (int k = 0; k < 6; ++k) {
        qq[k] = held(q[k]);
        s[k] = seed ? held(seed[k]) : 0;
        out->q[k] = (double)qq[k];
        out->seed[k] = (double)s[k];
    }
    tse_fk_result r;
    memset(&r, 0x5A, sizeof r);
    out->ret = (int)tse_fk(&geometry, qq, seed ? s : NULL, &r);
    out->status = (int)r.status;
    out->scissor = r.scissor;
    for (int k = 0; k < 6; ++k)
        out->pose[k] = (double)r.pose[k];
}
