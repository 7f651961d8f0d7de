/* Precision bridge, compiled once per precision: see kin_ops.h for the promise. */
#include <stdlib.h>

#include "kin_prec.h"
#include "tse/fk.h"
#include "tse/ik.h"
#include "tse/jacobian.h"
#include "tse/metrics.h"

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

static kin_ctx *create(const kin_param_values *p, tse_param_id *bad)
{
    *bad = TSE_PARAM_OK;
    kin_ctx *c = calloc(1, sizeof *c);
    if (!c)
        return NULL;
    tse_params *t = &c->params;
    /* Rounding to float can break a set that is valid in double (an angle next to 90 degrees, an
     * L beyond FLT_MAX): the library's own check on the rounded values decides. */
    t->L = (tse_real)p->v[TSE_PARAM_L];
    t->k1 = (tse_real)p->v[TSE_PARAM_K1];
    t->eta = (tse_real)p->v[TSE_PARAM_ETA];
    t->k3 = (tse_real)p->v[TSE_PARAM_K3];
    t->k4 = (tse_real)p->v[TSE_PARAM_K4];
    t->alpha_min = (tse_real)p->v[TSE_PARAM_ALPHA_MIN];
    t->alpha_max = (tse_real)p->v[TSE_PARAM_ALPHA_MAX];
    t->s_min = (tse_real)p->v[TSE_PARAM_S_MIN];
    t->s_max = (tse_real)p->v[TSE_PARAM_S_MAX];
    t->mu_min = (tse_real)p->v[TSE_PARAM_MU_MIN];
    t->nu_min = (tse_real)p->v[TSE_PARAM_NU_MIN];
    *bad = tse_geometry_init(&c->g, t);
    if (*bad != TSE_PARAM_OK) {
        free(c);
        return NULL;
    }
    return c;
}

static void destroy(kin_ctx *c)
{
    free(c);
}

static tse_status ik(const kin_ctx *c, const double pose[6], const double *seed_q, kin_ik_out *out)
{
    tse_real p[6], s[6];
    to_real(pose, p, 6);
    if (seed_q)
        to_real(seed_q, s, 6);
    tse_ik_result r;
    tse_ik(&c->g, p, seed_q ? s : NULL, &r);
    out->status = r.status;
    out->scissor = r.status == TSE_OK ? 0 : r.scissor;
    to_double(r.q, out->q, 6);
    out->iterations = r.iterations;
    out->fallbacks = r.fallbacks;
    return out->status;
}

static tse_status fk(const kin_ctx *c, const double q[6], const double *seed_pose, kin_fk_out *out)
{
    tse_real qq[6], s[6];
    to_real(q, qq, 6);
    if (seed_pose)
        to_real(seed_pose, s, 6);
    tse_fk_result r;
    tse_fk(&c->g, qq, seed_pose ? s : NULL, &r);
    out->status = r.status;
    out->scissor = r.status == TSE_OK ? 0 : r.scissor;
    out->iterations = r.iterations;
    for (int k = 0; k < 6; ++k)
        out->pose[k] = r.status == TSE_OK ? (double)r.pose[k] : (double)NAN;
    return out->status;
}

static tse_status jacobian(const kin_ctx *c, const double pose[6], kin_jacobian_out *out)
{
    tse_real p[6];
    to_real(pose, p, 6);
    for (int i = 0; i < 6; ++i) {
        out->sv[i] = (double)NAN;
        for (int j = 0; j < 6; ++j)
            out->J[i][j] = (double)NAN;
    }
    tse_ik_result r;
    out->status = tse_ik(&c->g, p, NULL, &r);
    out->scissor = out->status == TSE_OK ? 0 : r.scissor;
    if (out->status != TSE_OK)
        return out->status;
    tse_real J[6][6], s[6];
    out->status = tse_jacobian(&c->g, p, r.q, J);
    if (out->status != TSE_OK)
        return out->status;
    for (int i = 0; i < 6; ++i)
        to_double(J[i], out->J[i], 6);
    tse_singular_values(J, s);
    /* dp/dq is the inverse of dq/dp: its singular values are the reciprocals, order reversed. */
    for (int k = 0; k < 6; ++k)
        out->sv[k] = 1.0 / (double)s[5 - k];
    return TSE_OK;
}

static tse_status sigma_z(const kin_ctx *c, double z, double *sigma)
{
    tse_real s = (tse_real)NAN;
    const tse_status st = tse_sigma_z(&c->g, (tse_real)z, &s);
    *sigma = st == TSE_OK ? (double)s : (double)NAN;
    return st;
}

static tse_status haf(const kin_ctx *c, double z, double *h)
{
    tse_real v = (tse_real)NAN;
    const tse_status st = tse_haf(&c->params, (tse_real)z, &v);
    *h = st == TSE_OK ? (double)v : (double)NAN;
    return st;
}

static tse_status workspace_volume(const kin_ctx *c, int n_r, int n_phi, int n_z, const double orientation[3],
                                   long *reachable, long *total, double *volume)
{
    tse_real o[3], v = (tse_real)NAN;
    to_real(orientation, o, 3);
    const tse_status st = tse_workspace_volume(&c->g, n_r, n_phi, n_z, o, reachable, total, &v);
    *volume = (double)v;
    return st;
}

static tse_status workspace_cell(const kin_ctx *c, const int grid[3], int i, int k, double *volume)
{
    tse_real v = (tse_real)NAN;
    const tse_status st = tse_workspace_cell_volume(&c->g, grid[0], grid[1], grid[2], i, k, &v);
    *volume = (double)v;
    return st;
}

static tse_status workspace_point(const kin_ctx *c, const int grid[3], int i, int j, int k,
                                  const double orientation[3], double pose[6], int *scissor)
{
    tse_real o[3], p[6];
    to_real(orientation, o, 3);
    tse_status st = tse_workspace_pose(&c->g, grid[0], grid[1], grid[2], i, j, k, o, p);
    to_double(p, pose, 6);
    *scissor = 0;
    if (st != TSE_OK)
        return st;
    tse_ik_result r;
    st = tse_ik(&c->g, p, NULL, &r);
    *scissor = st == TSE_OK ? 0 : r.scissor;
    return st;
}

static tse_status profile(const kin_ctx *c, double z, kin_profile_out *out)
{
    tse_vertical_figures f;
    const tse_status st = tse_vertical_profile(&c->g, (tse_real)z, &f);
    to_double(f.sv, out->sv, 6);
    out->sigma_z = (double)f.sigma_z;
    out->mu_min = (double)f.mu_min;
    out->nu = (double)f.nu;
    return st;
}

static tse_status margins(const kin_ctx *c, const double pose[6], kin_margins_out *out)
{
    tse_real p[6];
    to_real(pose, p, 6);
    tse_ik_result r;
    out->status = tse_ik(&c->g, p, NULL, &r);
    out->scissor = out->status == TSE_OK ? 0 : r.scissor;
    tse_margin_result m;
    tse_margins(&c->g, p, &m);
    to_double(m.mu, out->mu, 3);
    out->nu = (double)m.nu;
    return out->status;
}

const kin_ops KIN_PREC(kin_ops) = {
    .name = TSE_REAL_NAME,
    .create = create,
    .destroy = destroy,
    .ik = ik,
    .fk = fk,
    .jacobian = jacobian,
    .sigma_z = sigma_z,
    .haf = haf,
    .workspace_volume = workspace_volume,
    .workspace_cell = workspace_cell,
    .workspace_point = workspace_point,
    .profile = profile,
    .margins = margins,
    .bench = kin_bench_run,
};
