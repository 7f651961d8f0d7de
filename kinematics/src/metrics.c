#include "tse/ik.h"
#include "tse/jacobian.h"
#include "tse/metrics.h"

tse_status tse_sigma_z(const tse_geometry *g, tse_real z, tse_real *sigma)
{
    *sigma = (tse_real)NAN;
    if (!isfinite(z))
        return TSE_INVALID;
    const tse_real pose[6] = {TSE_R(0.0), TSE_R(0.0), z, TSE_R(0.0), TSE_R(0.0), TSE_R(0.0)};
    tse_real C[3][3], q[6], J[6][6];
    tse_apex_points(g, pose, C);
    for (int i = 0; i < 3; ++i) {
        tse_scissor_solution s;
        const tse_status st = tse_scissor_solve(g, i, C[i], g->home_s, g->home_s, &s);
        if (st != TSE_OK)
            return st;
        q[2 * i] = s.s_a;
        q[2 * i + 1] = s.s_b;
    }
    const tse_status st = tse_jacobian(g, pose, q, J);
    if (st != TSE_OK)
        return st;
    /* All six slides move together along Z: the gain is 1 / |dq/dZ|. */
    tse_real n = TSE_R(0.0);
    for (int k = 0; k < 6; ++k)
        n += J[k][TSE_Z] * J[k][TSE_Z];
    *sigma = TSE_R(1.0) / tse_sqrt(n);
    return TSE_OK;
}

tse_status tse_haf(const tse_params *p, tse_real z, tse_real *haf)
{
    *haf = (tse_real)NAN;
    tse_params rigid = *p;
    rigid.k1 = TSE_R(1.0);
    tse_geometry gd, gr;
    if (tse_geometry_init(&gd, p) != TSE_PARAM_OK || tse_geometry_init(&gr, &rigid) != TSE_PARAM_OK)
        return TSE_INVALID;
    tse_real sd, sr;
    tse_status st = tse_sigma_z(&gd, z, &sd);
    if (st == TSE_OK)
        st = tse_sigma_z(&gr, z, &sr);
    if (st != TSE_OK)
        return st;
    *haf = sd / sr;
    return TSE_OK;
}

tse_status tse_workspace(const tse_geometry *g, int n_r, int n_phi, int n_z,
                         const tse_real orientation[3], long *reachable, long *total)
{
    *reachable = 0;
    *total = 0;
    if (n_r < 2 || n_phi < 1 || n_z < 2)
        return TSE_INVALID;
    for (int k = 0; k < 3; ++k)
        if (!isfinite(orientation[k]))
            return TSE_INVALID;
    const tse_real L = g->p.L;
    for (int k = 0; k < n_z; ++k) {
        const tse_real z = L * (tse_real)k / (tse_real)(n_z - 1);
        for (int i = 0; i < n_r; ++i) {
            const tse_real r = TSE_R(0.5) * L * (tse_real)i / (tse_real)(n_r - 1);
            for (int j = 0; j < n_phi; ++j) {
                const tse_real phi = TSE_R(2.0) * TSE_PI * (tse_real)j / (tse_real)n_phi;
                const tse_real pose[6] = {r * tse_cos(phi), r * tse_sin(phi), z,
                                          orientation[0], orientation[1], orientation[2]};
                tse_ik_result res;
                if (tse_ik(g, pose, NULL, &res) == TSE_OK)
                    ++*reachable;
                ++*total;
            }
        }
    }
    return TSE_OK;
}
