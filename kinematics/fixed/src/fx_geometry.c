/* The design in fixed point: the prototype's values, the contract's parameter rules with the
 * fixed build's ranges, and the geometry derived from them in integers (the board computes it
 * without a floating-point routine). */
#include "fx_math.h"
#include "tse/ik_fixed.h"
#include "tse/prototype.h"

/* tse/prototype.h's figures rounded to the formats (integer constant expressions: the conversion
 * happens at compile time, not on the board). */
#define FX_ROUND(x, scale) ((int32_t)((x) * (scale) + ((x) < 0 ? -0.5 : 0.5)))

void tse_fx_params_default(tse_fx_params *p)
{
    p->L = FX_ROUND(TSE_PROTO_L, 16777216.0);
    p->k1 = FX_ROUND(TSE_PROTO_K1, 1073741824.0);
    p->eta = FX_ROUND(TSE_PROTO_ETA, 268435456.0);
    p->k3 = FX_ROUND(TSE_PROTO_K3, 1073741824.0);
    p->k4 = FX_ROUND(TSE_PROTO_K4, 1073741824.0);
    p->alpha_min = FX_ROUND(TSE_PROTO_ALPHA_MIN, 268435456.0);
    p->alpha_max = FX_ROUND(TSE_PROTO_ALPHA_MAX, 268435456.0);
    p->s_min = FX_ROUND(TSE_PROTO_S_MIN, 16777216.0);
    p->s_max = FX_ROUND(TSE_PROTO_S_MAX, 16777216.0);
    p->mu_min = FX_ROUND(TSE_PROTO_MU_MIN, 1073741824.0);
    p->nu_min = FX_ROUND(TSE_PROTO_NU_MIN, 1073741824.0);
}

#define FX_HALF_PI 421657428 /* pi/2 in Q28, rounded down: |angle| <= it is below pi/2 */
#define FX_HALF_SQRT3 929887697 /* sqrt(3)/2 in Q30 */
/* The fixed build's ranges (ik_fixed.h): they keep every product of a solve inside 64 bits. */
#define FX_L_MAX (4 * TSE_FX_M)
#define FX_K1_MIN (TSE_FX_ONE / 8)
#define FX_R_MAX (4 * TSE_FX_M)
#define FX_S_BOX (8 * TSE_FX_M)

static int32_t ratio_of(int32_t len, int32_t k)
{
    return (int32_t)fx_shr((int64_t)len * k + (1 << 29), 30);
}

/* reach = L + 2 l0 sqrt(2 / (1 + c)) (geometry.h of the float build says why), Q24, with room
 * for its own rounding; -1 when it is beyond 8 m. */
static int64_t reach_of(int32_t L, int32_t l0, int32_t c)
{
    const int64_t one_c = (int64_t)TSE_FX_ONE + c; /* > 0: |eta| < 90 deg */
    const int64_t ratio = fx_div(2LL * TSE_FX_ONE, one_c, 30); /* 2 / (1 + c), Q30 */
    if (ratio > 64LL * TSE_FX_ONE)
        return -1;
    const int64_t root = fx_isqrt64((uint64_t)ratio << 18); /* Q24: ratio < 2^37, so 2^55 */
    const int64_t reach = L + fx_shr(2LL * l0 * root, 24);
    if (reach > FX_S_BOX)
        return -1;
    return reach + (reach >> 16) + 16;
}

/* The slide with s_A = s_B = s for the pose (0, 0, z, 0, 0, 0): the float build's
 * tse_vertical_slide, in Q24; -1 when that height has none on the branch. */
static int32_t vertical_slide(const tse_fx_geometry *g, int32_t z)
{
    int32_t se, ce;
    tse_fx_sincos(g->p.eta, &se, &ce);
    const int32_t d = g->r_top - g->r_act;
    const int64_t u0 = fx_shr((int64_t)d * se, 30);                                    /* Q24 */
    /* A = 1 - 2 g (1 + c) <= 64: Q24 */
    const int64_t A = (1LL << 24) - fx_shr(2LL * g->g * ((int64_t)TSE_FX_ONE + g->c), 32);
    const int64_t k = (int64_t)d * d + (int64_t)z * z - g->L2;                        /* Q48 */
    const int64_t disc = u0 * u0 - fx_mul64x32(k, (int32_t)A, 24);                    /* Q48 */
    if (disc < 0)
        return -1;
    const int64_t root = fx_isqrt64((uint64_t)disc);
    const int64_t cand[2] = {u0 + root, u0 - root};
    for (int j = 0; j < 2; ++j) {
        const int64_t s = fx_div(cand[j], A, 24);
        if (s > 0 && s < FX_S_BOX && (s - u0) * (fx_shr(s * A, 24) - u0) > 0)
            return (int32_t)s;
    }
    return -1;
}

static int inside(int64_t x, int64_t lo, int lo_closed, int64_t hi, int hi_closed)
{
    return (lo_closed ? x >= lo : x > lo) && (hi_closed ? x <= hi : x < hi);
}

tse_param_id tse_fx_geometry_init(tse_fx_geometry *g, const tse_fx_params *p)
{
    /* tse_params_check's rules, then the format's ranges, in the order of tse_param_id. */
    if (!inside(p->L, 0, 0, FX_L_MAX, 1))
        return TSE_PARAM_L;
    if (!inside(p->k1, FX_K1_MIN, 1, TSE_FX_ONE, 1))
        return TSE_PARAM_K1;
    if (!inside(p->eta, -FX_HALF_PI, 1, FX_HALF_PI, 1))
        return TSE_PARAM_ETA;
    const int32_t l0 = ratio_of(p->L, p->k1), r_act = ratio_of(p->L, p->k3), r_top = ratio_of(p->L, p->k4);
    int32_t s2e, c2e;
    tse_fx_sincos(2 * p->eta, &s2e, &c2e);
    if (reach_of(p->L, l0, c2e) < 0)
        return TSE_PARAM_ETA;
    if (!inside(p->k3, 0, 1, INT32_MAX, 1) || r_act > FX_R_MAX)
        return TSE_PARAM_K3;
    if (!inside(p->k4, 0, 0, INT32_MAX, 1) || r_top > FX_R_MAX || r_top == 0)
        return TSE_PARAM_K4;
    if (!inside(p->alpha_min, 0, 0, FX_HALF_PI, 1))
        return TSE_PARAM_ALPHA_MIN;
    if (!inside(p->alpha_max, p->alpha_min, 0, FX_HALF_PI, 1))
        return TSE_PARAM_ALPHA_MAX;
    if (!inside(p->s_min, 0, 1, INT32_MAX, 1))
        return TSE_PARAM_S_MIN;
    if (!inside(p->s_max, p->s_min, 0, FX_S_BOX, 1))
        return TSE_PARAM_S_MAX;
    if (!inside(p->mu_min, 0, 1, TSE_FX_ONE, 0))
        return TSE_PARAM_MU_MIN;
    if (!inside(p->nu_min, 0, 1, TSE_FX_ONE, 0))
        return TSE_PARAM_NU_MIN;

    g->p = *p;
    g->l0 = l0;
    g->r_act = r_act;
    g->r_top = r_top;
    /* k L in Q28 (Q30 x Q24 >> 26; at most 4 m): the slides are sensitive to the ball joints'
     * offsets. */
    g->r_top28 = (int32_t)fx_shr((int64_t)p->k4 * p->L + (1 << 25), 26);
    const int32_t r_act28 = (int32_t)fx_shr((int64_t)p->k3 * p->L + (1 << 25), 26);
    g->c = c2e;
    /* (1 - (1/k1)^2) / 4 with 1/k1 in Q24 (at most 8): Q48, then Q26. */
    const int64_t inv_k1 = fx_div(TSE_FX_ONE, p->k1, 24);
    g->g = (int32_t)fx_shr((1LL << 48) - inv_k1 * inv_k1 + (1LL << 23), 24);
    g->L2 = (int64_t)p->L * p->L;
    /* w = 2 l0 cos(alpha) falls as alpha rises: the stops are a band on w^2. */
    int32_t s_a, c_a;
    tse_fx_sincos(p->alpha_min, &s_a, &c_a);
    const int64_t w_hi = fx_shr(2LL * l0 * c_a + (1 << 29), 30);
    tse_fx_sincos(p->alpha_max, &s_a, &c_a);
    const int64_t w_lo = fx_shr(2LL * l0 * c_a + (1 << 29), 30);
    g->w_lo2 = w_lo * w_lo;
    g->w_hi2 = w_hi * w_hi;
    const int64_t reach = reach_of(p->L, l0, c2e);
    g->reach2 = reach * reach;
    g->step_max = p->L / 10;
    g->step_max2 = (int64_t)g->step_max * g->step_max;
    /* The slides carry the rounding of F's terms (of the size of span^2) through M's inverse, as
     * in the float build (scissor_core.h, scissor_mu_clear), here a few units of 2^-24 m per
     * metre: eps = 2^-22. */
    const int64_t span = (int64_t)p->L + r_act + r_top;
    g->mu_guard = fx_shr(span * span, 22);
    g->s_box = FX_S_BOX;

    /* Exact values at 0, 120 and 240 degrees keep the three scissors symmetric. */
    const int32_t cb[3] = {TSE_FX_ONE, -TSE_FX_ONE / 2, -TSE_FX_ONE / 2};
    const int32_t sb[3] = {0, FX_HALF_SQRT3, -FX_HALF_SQRT3};
    int32_t se, ce;
    tse_fx_sincos(p->eta, &se, &ce);
    for (int i = 0; i < 3; ++i) {
        tse_fx_scissor_frame *f = &g->sc[i];
        const int32_t er[2] = {cb[i], sb[i]}; /* Q30 */
        const int32_t et[2] = {-sb[i], cb[i]};
        for (int k = 0; k < 2; ++k) {
            f->o[k] = (int32_t)fx_shr((int64_t)r_act28 * er[k] + (1 << 29), 30);
            f->a[k] = (int32_t)fx_shr((int64_t)ce * et[k] + (int64_t)se * er[k] + (1 << 29), 30);
            f->b[k] = (int32_t)fx_shr(-(int64_t)ce * et[k] + (int64_t)se * er[k] + (1 << 29), 30);
        }
    }
    int32_t sh, ch;
    tse_fx_sincos((int32_t)(((int64_t)p->alpha_min + p->alpha_max) / 2), &sh, &ch);
    const int32_t z_home = ratio_of(p->L, sh);
    g->home_s = vertical_slide(g, z_home);
    if (g->home_s < 0)
        g->home_s = l0 / 2;
    return TSE_PARAM_OK;
}
