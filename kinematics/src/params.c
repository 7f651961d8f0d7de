#include "tse/params.h"

#include "tse/prototype.h"

void tse_params_default(tse_params *p)
{
    p->L = (tse_real)TSE_PROTO_L;
    p->k1 = (tse_real)TSE_PROTO_K1;
    p->eta = (tse_real)TSE_PROTO_ETA;
    p->k3 = (tse_real)TSE_PROTO_K3;
    p->k4 = (tse_real)TSE_PROTO_K4;
    p->alpha_min = (tse_real)TSE_PROTO_ALPHA_MIN;
    p->alpha_max = (tse_real)TSE_PROTO_ALPHA_MAX;
    p->s_min = (tse_real)TSE_PROTO_S_MIN;
    p->s_max = (tse_real)TSE_PROTO_S_MAX;
    p->mu_min = (tse_real)TSE_PROTO_MU_MIN;
    p->nu_min = (tse_real)TSE_PROTO_NU_MIN;
}

/* Written as "accept when inside" so that NaN, which fails every comparison, is rejected too. */
static int inside(tse_real x, tse_real lo, int lo_closed, tse_real hi, int hi_closed)
{
    if (!isfinite(x))
        return 0;
    int above = lo_closed ? (x >= lo) : (x > lo);
    int below = hi_closed ? (x <= hi) : (x < hi);
    return above && below;
}

tse_param_id tse_params_check(const tse_params *p)
{
    const tse_real right = TSE_PI / TSE_R(2.0);
    const tse_real big = (tse_real)INFINITY;

    if (!inside(p->L, TSE_R(0.0), 0, big, 0))
        return TSE_PARAM_L;
    if (!inside(p->k1, TSE_R(0.0), 0, TSE_R(1.0), 1))
        return TSE_PARAM_K1;
    if (!inside(p->eta, -right, 0, right, 0))
        return TSE_PARAM_ETA;
    if (!inside(p->k3, TSE_R(0.0), 1, big, 0))
        return TSE_PARAM_K3;
    if (!inside(p->k4, TSE_R(0.0), 0, big, 0))
        return TSE_PARAM_K4;
    if (!inside(p->alpha_min, TSE_R(0.0), 0, right, 0))
        return TSE_PARAM_ALPHA_MIN;
    if (!inside(p->alpha_max, p->alpha_min, 0, right, 0))
        return TSE_PARAM_ALPHA_MAX;
    if (!inside(p->s_min, TSE_R(0.0), 1, big, 0))
        return TSE_PARAM_S_MIN;
    if (!inside(p->s_max, p->s_min, 0, big, 0))
        return TSE_PARAM_S_MAX;
    if (!inside(p->mu_min, TSE_R(0.0), 1, TSE_R(1.0), 0))
        return TSE_PARAM_MU_MIN;
    if (!inside(p->nu_min, TSE_R(0.0), 1, TSE_R(1.0), 0))
        return TSE_PARAM_NU_MIN;
    return TSE_PARAM_OK;
}
