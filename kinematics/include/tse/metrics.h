/* Design metrics of the paper: vertical spatial gear ratio, HAF, workspace percentage. */
#ifndef TSE_METRICS_H
#define TSE_METRICS_H

#include "tse/geometry.h"
#include "tse/status.h"

#define tse_sigma_z TSE_NS(tse_sigma_z)
#define tse_haf TSE_NS(tse_haf)
#define tse_workspace TSE_NS(tse_workspace)
#define tse_workspace_pose TSE_NS(tse_workspace_pose)
#define tse_workspace_count TSE_NS(tse_workspace_count)
#define tse_workspace_cell_volume TSE_NS(tse_workspace_cell_volume)
#define tse_workspace_volume TSE_NS(tse_workspace_volume)
#define tse_vertical_profile TSE_NS(tse_vertical_profile)
#define tse_margins TSE_NS(tse_margins)

/* sigma_z = 1 / (sqrt(6) |ds/dZ|) at (0, 0, z, 0, 0, 0).  Limits are not applied: the metric is a
 * property of the branch solution.  TSE_UNREACHABLE when no branch solution exists at z. */
tse_status tse_sigma_z(const tse_geometry *g, tse_real z, tse_real *sigma);

/* HAF(z) = sigma_z(z; p) / sigma_z(z; p with k1 = 1). */
tse_status tse_haf(const tse_params *p, tse_real z, tse_real *haf);

/* Counts reachable points of the paper's cylindrical grid at the fixed orientation
 * (roll, pitch, yaw): r_i = (L/2) i/(n_r-1), phi_j = 2 pi j/n_phi, Z_k = L k/(n_z-1).
 * Returns TSE_INVALID for n_r < 2, n_phi < 1 or n_z < 2, or a non-finite orientation. */
tse_status tse_workspace(const tse_geometry *g, int n_r, int n_phi, int n_z,
                         const tse_real orientation[3], long *reachable, long *total);

/* Point (i, j, k) of that grid as a pose, formed with the same expressions tse_workspace uses, so
 * that tse_ik (no seed) on every point counts exactly what tse_workspace counts: this is how a
 * caller draws the workspace or spreads a count over threads.  TSE_INVALID for a grid
 * tse_workspace refuses, an index outside it (0 <= i < n_r, 0 <= j < n_phi, 0 <= k < n_z), or a
 * non-finite orientation; the pose is then NaN. */
tse_status tse_workspace_pose(const tse_geometry *g, int n_r, int n_phi, int n_z, int i, int j, int k,
                              const tse_real orientation[3], tse_real pose[6]);

/* tse_workspace's count, faster: before solving a point it looks whether every ball joint is within
 * the scissor heights the stops allow (L sin alpha_min .. L sin alpha_max) of some midpoint of A
 * and B that the strokes allow, a necessary condition of passing the contract's checks; a point
 * that misses it by more than a rounding margin is counted unreachable without solving, the
 * others go to tse_ik as in tse_workspace.  So the count is tse_workspace's exactly (the
 * kinematics tests compare them), at a fraction of the time where most of the grid is out of
 * reach.  Only the count: a screened point's status is not known.  Same arguments and refusals. */
tse_status tse_workspace_count(const tse_geometry *g, int n_r, int n_phi, int n_z, const tse_real orientation[3],
                               long *reachable, long *total);

/* The volume [m^3] that point (i, j, k) of that grid stands for, the same for every j: its cell of
 * the cylinder r <= L/2, 0 <= Z <= L, cut halfway between neighbouring points in r and in Z (at the
 * axis, the rim, the floor and the top the cell ends there) and into n_phi equal sectors,
 *   (pi / n_phi) (r_hi^2 - r_lo^2) (Z_hi - Z_lo),
 * so that the cells of all points fill the cylinder, pi L^3 / 4, without gap or overlap.  Its
 * resolution: dr = L / (2 (n_r - 1)), dZ = L / (n_z - 1), an arc of pi L / n_phi at the rim.
 * TSE_INVALID (and NaN) for a grid or index tse_workspace_pose refuses. */
tse_status tse_workspace_cell_volume(const tse_geometry *g, int n_r, int n_phi, int n_z, int i, int k,
                                     tse_real *volume);

/* tse_workspace_count's count, and the reachable volume of the plate's centre at that orientation
 * [m^3]: the sum of the cells (tse_workspace_cell_volume) of the reachable points.  The workspace
 * as a size, so that designs of different L compare (the fraction is the same for a design scaled
 * as a whole).  Same arguments and refusals as tse_workspace_count; 0 and NaN when refused. */
tse_status tse_workspace_volume(const tse_geometry *g, int n_r, int n_phi, int n_z, const tse_real orientation[3],
                                long *reachable, long *total, tse_real *volume);

/* The paper's singular-value figures at one height of the vertical axis, (0, 0, z, 0, 0, 0), of the
 * branch solution (no limit applied, as tse_sigma_z). */
typedef struct {
    tse_real s;       /* the common slide position [m] */
    tse_real sv[6];   /* singular values of dp/dq, descending (as tse-kin jacobian prints them) */
    tse_real sigma_z; /* tse_sigma_z: the singular value along the all-slides-together motion */
    tse_real mu_min;  /* smallest type-1 margin of the three scissors */
    tse_real nu;      /* type-2 Hadamard ratio (rotation columns of dF/dp divided by r_top) */
} tse_vertical_figures;

/* TSE_INVALID for a non-finite z, TSE_UNREACHABLE when no branch solution exists at z,
 * TSE_SINGULAR when some M_i is singular there (the figures are NaN in every case but TSE_OK). */
tse_status tse_vertical_profile(const tse_geometry *g, tse_real z, tse_vertical_figures *out);

/* Both singularity margins of a pose whatever its limits say: each scissor's solution on the
 * branch, found from the symmetric home as tse_ik finds it without a seed, and its type-1 margin;
 * with all three, the type-2 ratio.  This is where singularities lie, inside or outside the
 * workspace (tse_ik reports a margin only while the earlier checks pass).  Returns TSE_OK when all
 * three scissors have a branch solution; otherwise the first failing scissor's status
 * (TSE_INVALID, TSE_UNREACHABLE, TSE_NOCONVERGE) in out->status and out->scissor (1..3), with
 * NaN for that scissor's margin and for nu. */
typedef struct {
    tse_status status;
    int scissor;    /* first scissor without a branch solution (1..3), 0 when all have one */
    tse_real q[6];  /* the branch solutions (NaN where none) */
    tse_real mu[3]; /* type-1 margin of each scissor (NaN where no solution) */
    tse_real nu;    /* type-2 Hadamard ratio, NaN unless all three have a solution */
} tse_margin_result;

tse_status tse_margins(const tse_geometry *g, const tse_real pose[6], tse_margin_result *out);

#endif
