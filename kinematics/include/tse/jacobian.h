/* Differential kinematics: analytic dq/dp, the constraint Jacobian dF/dp, singular values. */
#ifndef TSE_JACOBIAN_H
#define TSE_JACOBIAN_H

#include "tse/geometry.h"
#include "tse/status.h"

#define tse_constraint_jacobians TSE_NS(tse_constraint_jacobians)
#define tse_jacobian TSE_NS(tse_jacobian)
#define tse_hadamard_ratio TSE_NS(tse_hadamard_ratio)
#define tse_singular_values TSE_NS(tse_singular_values)

/* Fp = dF/dp (rows F1_1, F2_1, F1_2, ..., columns X, Y, Z, roll, pitch, yaw) and the 2x2 blocks
 * M_i = dF_i/d(s_Ai, s_Bi) at pose p with slides q. */
void tse_constraint_jacobians(const tse_geometry *g, const tse_real pose[6], const tse_real q[6],
                              tse_real Fp[6][6], tse_real M[3][2][2]);

/* J = dq/dp at (p, q), analytic: ds_i/dp = -M_i^-1 dF_i/dp.  TSE_SINGULAR if some M_i is
 * singular, TSE_INVALID for non-finite input. */
tse_status tse_jacobian(const tse_geometry *g, const tse_real pose[6], const tse_real q[6],
                        tse_real J[6][6]);

/* |det A| / prod(row norms) of a 6x6 matrix: 1 for orthogonal rows, 0 when singular. */
tse_real tse_hadamard_ratio(const tse_real A[6][6]);

/* Singular values of a 6x6 matrix, descending, from the eigenvalues of A^T A (cyclic Jacobi). */
void tse_singular_values(const tse_real A[6][6], tse_real sv[6]);

#endif
