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

tse_status tse_workspace_pose(const tse_geometry *g, int n_r, int n_phi, int n_z, int i, int j, int k,
                              const tse_real orientation[3], tse_real pose[6])
{
    for (int c = 0; c < 6; ++c)
        pose[c] = (tse_real)NAN;
    if (n_r < 2 || n_phi < 1 || n_z < 2 || i < 0 || i >= n_r || j < 0 || j >= n_phi || k < 0 || k >= n_z)
        return TSE_INVALID;
    for (int c = 0; c < 3; ++c)
        if (!isfinite(orientation[c]))
            return TSE_INVALID;
    /* Term for term tse_workspace's expressions: in float a regrouped product could round a point
     * across a threshold, and the points would no longer add up to tse_workspace's count. */
    const tse_real L = g->p.L;
    const tse_real z = L * (tse_real)k / (tse_real)(n_z - 1);
    const tse_real r = TSE_R(0.5) * L * (tse_real)i / (tse_real)(n_r - 1);
    const tse_real phi = TSE_R(2.0) * TSE_PI * (tse_real)j / (tse_real)n_phi;
    pose[0] = r * tse_cos(phi);
    pose[1] = r * tse_sin(phi);
    pose[2] = z;
    pose[3] = orientation[0];
    pose[4] = orientation[1];
    pose[5] = orientation[2];
    return TSE_OK;
}

/* Each scissor's branch solution for the ball joints of `pose`, from the symmetric home as tse_ik
 * starts without a seed; every scissor is solved, ok[i] says which have one.  Returns the first
 * failing scissor's status, its index (0-based) in *failed (-1 when all three are solved). */
static tse_status branch_solutions(const tse_geometry *g, const tse_real pose[6], tse_scissor_solution sol[3],
                                   int ok[3], int *failed)
{
    tse_real C[3][3];
    tse_apex_points(g, pose, C);
    tse_status first = TSE_OK;
    *failed = -1;
    for (int i = 0; i < 3; ++i) {
        const tse_status st = tse_scissor_solve(g, i, C[i], g->home_s, g->home_s, &sol[i]);
        ok[i] = st == TSE_OK;
        if (st != TSE_OK && first == TSE_OK) {
            first = st;
            *failed = i;
        }
    }
    return first;
}

/* kinematics.md's type-2 ratio: dF/dp with its rotation columns divided by r_top, so that every
 * column is in metres of ball-joint travel. */
static tse_real type2_ratio(const tse_geometry *g, const tse_real pose[6], const tse_real q[6])
{
    tse_real Fp[6][6], M[3][2][2];
    tse_constraint_jacobians(g, pose, q, Fp, M);
    for (int r = 0; r < 6; ++r)
        for (int c = 3; c < 6; ++c)
            Fp[r][c] *= g->inv_r_top;
    return tse_hadamard_ratio((const tse_real(*)[6])Fp);
}

tse_status tse_vertical_profile(const tse_geometry *g, tse_real z, tse_vertical_figures *out)
{
    out->s = out->sigma_z = out->mu_min = out->nu = (tse_real)NAN;
    for (int k = 0; k < 6; ++k)
        out->sv[k] = (tse_real)NAN;
    if (!isfinite(z))
        return TSE_INVALID;
    const tse_real pose[6] = {TSE_R(0.0), TSE_R(0.0), z, TSE_R(0.0), TSE_R(0.0), TSE_R(0.0)};
    tse_scissor_solution sol[3];
    int ok[3], failed;
    tse_status st = branch_solutions(g, pose, sol, ok, &failed);
    if (st != TSE_OK)
        return st;
    tse_real q[6], J[6][6], s[6];
    tse_real mu = sol[0].mu;
    for (int i = 0; i < 3; ++i) {
        q[2 * i] = sol[i].s_a;
        q[2 * i + 1] = sol[i].s_b;
        mu = sol[i].mu < mu ? sol[i].mu : mu;
    }
    st = tse_jacobian(g, pose, q, J);
    if (st != TSE_OK)
        return st;
    tse_singular_values((const tse_real(*)[6])J, s);
    /* dp/dq is the inverse of dq/dp: its singular values are the reciprocals, order reversed. */
    for (int k = 0; k < 6; ++k)
        out->sv[k] = TSE_R(1.0) / s[5 - k];
    tse_real n = TSE_R(0.0);
    for (int k = 0; k < 6; ++k)
        n += J[k][TSE_Z] * J[k][TSE_Z];
    /* tse_sigma_z's figure from the same Jacobian (it solves the same branch from the same seed). */
    out->sigma_z = TSE_R(1.0) / tse_sqrt(n);
    out->s = q[0];
    out->mu_min = mu;
    out->nu = type2_ratio(g, pose, q);
    return TSE_OK;
}

tse_status tse_margins(const tse_geometry *g, const tse_real pose[6], tse_margin_result *out)
{
    out->status = TSE_OK;
    out->scissor = 0;
    out->nu = (tse_real)NAN;
    for (int k = 0; k < 6; ++k)
        out->q[k] = (tse_real)NAN;
    for (int i = 0; i < 3; ++i)
        out->mu[i] = (tse_real)NAN;
    for (int k = 0; k < 6; ++k)
        if (!isfinite(pose[k])) {
            out->status = TSE_INVALID;
            out->scissor = 1;
            return out->status;
        }
    tse_scissor_solution sol[3];
    int ok[3], failed;
    const tse_status st = branch_solutions(g, pose, sol, ok, &failed);
    for (int i = 0; i < 3; ++i) {
        if (!ok[i])
            continue;
        out->q[2 * i] = sol[i].s_a;
        out->q[2 * i + 1] = sol[i].s_b;
        out->mu[i] = sol[i].mu;
    }
    if (st != TSE_OK) {
        out->status = st;
        out->scissor = failed + 1;
        return st;
    }
    out->nu = type2_ratio(g, pose, out->q);
    return TSE_OK;
}

/* Squared distance from p to the segment [a, b] in the plane. */
static tse_real segment_dist2(const tse_real p[2], const tse_real a[2], const tse_real b[2])
{
    const tse_real ab[2] = {b[0] - a[0], b[1] - a[1]}, ap[2] = {p[0] - a[0], p[1] - a[1]};
    const tse_real len2 = ab[0] * ab[0] + ab[1] * ab[1];
    tse_real t = len2 > TSE_R(0.0) ? (ap[0] * ab[0] + ap[1] * ab[1]) / len2 : TSE_R(0.0);
    t = t < TSE_R(0.0) ? TSE_R(0.0) : t > TSE_R(1.0) ? TSE_R(1.0) : t;
    const tse_real d[2] = {ap[0] - t * ab[0], ap[1] - t * ab[1]};
    return d[0] * d[0] + d[1] * d[1];
}

/* Whether ball joint C may belong to a solution of scissor i within the strokes and the stops.
 *
 * F1 puts C's foot on the bisector of AB, so C is at the distance h = |C - D| from the midpoint
 * D = O + (s_A a + s_B b)/2 of AB, and F2 makes that distance the scissor's height L sin(alpha)
 * (|AC|^2 - (w/2)^2 = L^2 - (L/l0)^2 (w/2)^2).  The strokes keep D in a parallelogram of the base
 * plane (a segment when eta = 0), the stops keep h in [h_lo, h_hi]: no solution passes both when
 * C's distances to that parallelogram all lie outside the band. */
static int scissor_may_reach(const tse_geometry *g, int i, const tse_real C[3], tse_real h_lo2, tse_real h_hi2)
{
    const tse_scissor_frame *f = &g->sc[i];
    const tse_real s[2] = {TSE_R(0.5) * g->p.s_min, TSE_R(0.5) * g->p.s_max};
    tse_real V[4][2]; /* corners in order round the parallelogram: (lo,lo), (hi,lo), (hi,hi), (lo,hi) */
    static const int ca[4] = {0, 1, 1, 0}, cb[4] = {0, 0, 1, 1};
    for (int k = 0; k < 4; ++k)
        for (int c = 0; c < 2; ++c)
            V[k][c] = f->o[c] + s[ca[k]] * f->a[c] + s[cb[k]] * f->b[c];
    tse_real near2 = TSE_R(0.0), far2 = TSE_R(0.0);
    int sign = 0, inside = 1;
    for (int k = 0; k < 4; ++k) {
        const tse_real *p = V[k], *q = V[(k + 1) % 4];
        const tse_real cross = (q[0] - p[0]) * (C[1] - p[1]) - (q[1] - p[1]) * (C[0] - p[0]);
        const int sg = cross > TSE_R(0.0) ? 1 : cross < TSE_R(0.0) ? -1 : 0;
        if (sg == 0 || (sign != 0 && sg != sign))
            inside = 0;
        sign = sg != 0 ? sg : sign;
        const tse_real e2 = segment_dist2(C, p, q);
        near2 = k == 0 || e2 < near2 ? e2 : near2;
        const tse_real v2 = (C[0] - p[0]) * (C[0] - p[0]) + (C[1] - p[1]) * (C[1] - p[1]);
        far2 = v2 > far2 ? v2 : far2;
    }
    if (inside)
        near2 = TSE_R(0.0);
    const tse_real z2 = C[2] * C[2];
    return z2 + near2 <= h_hi2 && z2 + far2 >= h_lo2;
}

tse_status tse_workspace_cell_volume(const tse_geometry *g, int n_r, int n_phi, int n_z, int i, int k,
                                     tse_real *volume)
{
    *volume = (tse_real)NAN;
    if (n_r < 2 || n_phi < 1 || n_z < 2 || i < 0 || i >= n_r || k < 0 || k >= n_z)
        return TSE_INVALID;
    const tse_real L = g->p.L, R = TSE_R(0.5) * L;
    const tse_real dr = R / (tse_real)(n_r - 1), dz = L / (tse_real)(n_z - 1);
    const tse_real r_lo = i == 0 ? TSE_R(0.0) : ((tse_real)i - TSE_R(0.5)) * dr;
    const tse_real r_hi = i == n_r - 1 ? R : ((tse_real)i + TSE_R(0.5)) * dr;
    const tse_real z_lo = k == 0 ? TSE_R(0.0) : ((tse_real)k - TSE_R(0.5)) * dz;
    const tse_real z_hi = k == n_z - 1 ? L : ((tse_real)k + TSE_R(0.5)) * dz;
    *volume = TSE_PI / (tse_real)n_phi * (r_hi * r_hi - r_lo * r_lo) * (z_hi - z_lo);
    return TSE_OK;
}

tse_status tse_workspace_count(const tse_geometry *g, int n_r, int n_phi, int n_z, const tse_real orientation[3],
                               long *reachable, long *total)
{
    tse_real volume;
    return tse_workspace_volume(g, n_r, n_phi, n_z, orientation, reachable, total, &volume);
}

tse_status tse_workspace_volume(const tse_geometry *g, int n_r, int n_phi, int n_z, const tse_real orientation[3],
                                long *reachable, long *total, tse_real *volume)
{
    *reachable = 0;
    *total = 0;
    *volume = (tse_real)NAN;
    tse_real pose[6];
    if (tse_workspace_pose(g, n_r, n_phi, n_z, 0, 0, 0, orientation, pose) != TSE_OK)
        return TSE_INVALID;
    /* The band widened by a margin far beyond the solver's error (1e-9 m in double, 2e-6 m in
     * float, times the slides' lever on the height), so that rounding never screens out a point
     * tse_ik would accept: points that close to the boundary are simply solved. */
    const tse_real L = g->p.L;
    const tse_real margin = (sizeof(tse_real) < sizeof(double) ? TSE_R(1e-4) : TSE_R(1e-6)) * L;
    const tse_real h_lo = L * tse_sin(g->p.alpha_min) - margin, h_hi = L * tse_sin(g->p.alpha_max) + margin;
    const tse_real h_lo2 = h_lo > TSE_R(0.0) ? h_lo * h_lo : TSE_R(0.0), h_hi2 = h_hi * h_hi;
    /* One addition per ring of cells, not per point: in float a sum of some 10^4 cells would
     * lose digits the count keeps. */
    tse_real sum = TSE_R(0.0);
    for (int k = 0; k < n_z; ++k)
        for (int i = 0; i < n_r; ++i) {
            long ring = 0;
            for (int j = 0; j < n_phi; ++j) {
                (void)tse_workspace_pose(g, n_r, n_phi, n_z, i, j, k, orientation, pose);
                ++*total;
                tse_real C[3][3];
                tse_apex_points(g, pose, C);
                int may = 1;
                for (int s = 0; s < 3 && may; ++s)
                    may = scissor_may_reach(g, s, C[s], h_lo2, h_hi2);
                tse_ik_result res;
                if (may && tse_ik(g, pose, NULL, &res) == TSE_OK)
                    ++ring;
            }
            if (ring > 0) {
                tse_real cell;
                (void)tse_workspace_cell_volume(g, n_r, n_phi, n_z, i, k, &cell);
                sum += (tse_real)ring * cell;
                *reachable += ring;
            }
        }
    *volume = sum;
    return TSE_OK;
}
