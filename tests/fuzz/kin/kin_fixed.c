#include "kin_fixed.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "fuzz_target.h"
#include "kin_ref.h"
#include "tse/ik_fixed.h"
#include "tse/status.h"

static const double SCALE[SIDE_NPARAMS] = {TSE_FX_M,   TSE_FX_ONE, TSE_FX_RAD, TSE_FX_ONE, TSE_FX_ONE, TSE_FX_RAD,
                                           TSE_FX_RAD, TSE_FX_M,   TSE_FX_M,   TSE_FX_ONE, TSE_FX_ONE};

/* x * scale rounded, when it fits in int32 (NaN and infinities do not). */
static int fits(double x, double scale, int32_t *out)
{
    const double y = nearbyint(x * scale);
    if (!(y >= -2147483647.0 && y <= 2147483647.0))
        return 0;
    *out = (int32_t)y;
    return 1;
}

static int pose_fx(const double in[6], int32_t out[6], double held[6])
{
    for (int k = 0; k < 6; ++k) {
        const double s = k < 3 ? TSE_FX_M : TSE_FX_RAD;
        if (!fits(in[k], s, &out[k]))
            return 0;
        held[k] = out[k] / s;
    }
    return 1;
}

void kin_fixed_run(const kin_case *c)
{
    tse_fx_params fp;
    int32_t *f[SIDE_NPARAMS] = {&fp.L,         &fp.k1,    &fp.eta,   &fp.k3,     &fp.k4,    &fp.alpha_min,
                                &fp.alpha_max, &fp.s_min, &fp.s_max, &fp.mu_min, &fp.nu_min};
    double held[SIDE_NPARAMS];
    for (int k = 0; k < SIDE_NPARAMS; ++k) {
        if (!fits(c->params[k], SCALE[k], f[k]))
            return; /* not a design the formats hold */
        held[k] = *f[k] / SCALE[k];
    }
    tse_fx_geometry g;
    const tse_param_id bad = tse_fx_geometry_init(&g, &fp);
    KIN_CHECK(bad >= TSE_PARAM_OK && bad < TSE_PARAM_COUNT);
    if (bad != TSE_PARAM_OK)
        return;
    double dheld[SIDE_NPARAMS];
    KIN_CHECK(side_init_d(held, dheld) == 0); /* the fixed ranges are within the contract's */
    ref_design d;
    ref_design_init(&d, dheld, 1, c->plausible_params); /* the float build's bands: the fixed's size */

    int32_t px[6], sx[6];
    double pose[6], seed[6];
    if (!pose_fx(c->pose, px, pose))
        return;
    int seeded = 0;
    if (c->ik_seeded && !c->warm_ik_seed) {
        for (int k = 0; k < 6; ++k)
            if (!fits(c->ik_seed[k], TSE_FX_M, &sx[k]))
                return;
        seeded = 1;
    }
    tse_fx_ik_result r;
    const tse_status st = tse_fx_ik(&g, px, seeded ? sx : NULL, &r);
    ref_context("fixed IK of " "(%d, %d, %d, %d, %d, %d)" " seeded %d", px[0], px[1], px[2], px[3], px[4], px[5], seeded);
    KIN_CHECK(st == r.status && st >= TSE_OK && st < TSE_STATUS_COUNT && st != TSE_NOCONVERGE);
    KIN_CHECK(st == TSE_OK ? r.scissor == 0 : r.scissor >= 1 && r.scissor <= 3);
    if (seeded) {
        int beyond = 0;
        for (int k = 0; k < 6; ++k)
            beyond |= sx[k] > g.s_box || sx[k] < -g.s_box;
        KIN_CHECK((st == TSE_INVALID) == beyond);
        if (beyond)
            return;
        for (int k = 0; k < 6; ++k)
            seed[k] = sx[k] / (double)TSE_FX_M;
    } else {
        KIN_CHECK(st != TSE_INVALID);
    }
    if (st == TSE_OK) {
        for (int k = 0; k < 6; ++k)
            KIN_CHECK(r.q[k] >= fp.s_min && r.q[k] <= fp.s_max);
        for (int i = 0; i < 3; ++i)
            KIN_CHECK(r.mu[i] >= fp.mu_min);
        KIN_CHECK(r.nu >= fp.nu_min);
    }
    side_ik rd;
    side_ik_d(pose, seeded ? seed : NULL, &rd);
    ref_context("fixed IK of (%d, %d, %d, %d, %d, %d) seeded %d: %s/%d, slides (%d, %d, %d, %d, %d, %d); double %s/%d",
                px[0], px[1], px[2], px[3], px[4], px[5], seeded, tse_status_name(st), r.scissor, r.q[0], r.q[1],
                r.q[2], r.q[3], r.q[4], r.q[5], tse_status_name((tse_status)rd.status), rd.scissor);
    if (!ref_comparable(&d, pose))
        return;
    orc_result o;
    ref_classify(&d, pose, &o);
    if (o.ambiguous || o.multi)
        return;
    KIN_CHECK((int)st == rd.status);
    if (st != TSE_OK && st != TSE_DEGENERATE)
        KIN_CHECK(r.scissor == rd.scissor);
    if (st == TSE_OK && rd.status == TSE_OK && o.mu[0] >= 0.1L && o.mu[1] >= 0.1L && o.mu[2] >= 0.1L &&
        ref_well_conditioned(&d, pose, rd.q))
        for (int k = 0; k < 6; ++k)
            KIN_CHECK(fabs(r.q[k] / (double)TSE_FX_M - rd.q[k]) <= 1e-6);
}
