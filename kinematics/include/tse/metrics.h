/* Design metrics of the paper: vertical spatial gear ratio, HAF, workspace percentage. */
#ifndef TSE_METRICS_H
#define TSE_METRICS_H

#include "tse/geometry.h"
#include "tse/status.h"

#define tse_sigma_z TSE_NS(tse_sigma_z)
#define tse_haf TSE_NS(tse_haf)
#define tse_workspace TSE_NS(tse_workspace)

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

#endif
