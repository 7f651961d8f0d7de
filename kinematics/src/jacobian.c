#include "kin_internal.h"
#include "tse/ik.h"
#include "tse/jacobian.h"

void tse_constraint_rows(const tse_geometry *g, const tse_real pose[6], const tse_plate *frame,
                         const tse_real C[3][3], const tse_real q[6], tse_real rot_scale,
                         tse_real Fp[6][6], tse_real M[3][2][2])
{
    for (int i = 0; i < 3; ++i) {
        tse_scissor_local loc;
        const tse_real s_a = q[2 * i], s_b = q[2 * i + 1];
        const tse_scissor_frame *f = &g->sc[i];
        tse_scissor_localize(g, i, C[i], &loc);
        if (M != NULL) {
            tse_real F[2];
            tse_scissor_eval(g, &loc, s_a, s_b, F, M[i]);
        }

        /* Gradients with respect to the ball joint: F1 = |AC|^2 - |BC|^2, F2 = |AC|^2 - ... */
        tse_real grad[2][3];
        for (int k = 0; k < 2; ++k) {
            grad[0][k] = TSE_R(-2.0) * s_a * f->a[k] + TSE_R(2.0) * s_b * f->b[k];
            grad[1][k] = TSE_R(-2.0) * s_a * f->a[k] + TSE_R(2.0) * loc.d[k];
        }
        grad[0][2] = TSE_R(0.0);
        grad[1][2] = TSE_R(2.0) * loc.d[2];

        /* dC/dtheta_k = axis_k x (C - position). */
        const tse_real rc[3] = {C[i][0] - pose[0], C[i][1] - pose[1], C[i][2] - pose[2]};
        tse_real dC[3][3];
        for (int k = 0; k < 3; ++k) {
            const tse_real *ax = frame->axes[k];
            dC[k][0] = rot_scale * (ax[1] * rc[2] - ax[2] * rc[1]);
            dC[k][1] = rot_scale * (ax[2] * rc[0] - ax[0] * rc[2]);
            dC[k][2] = rot_scale * (ax[0] * rc[1] - ax[1] * rc[0]);
        }
        for (int r = 0; r < 2; ++r) {
            tse_real *row = Fp[2 * i + r];
            for (int k = 0; k < 3; ++k) {
                row[k] = grad[r][k];
                row[3 + k] = grad[r][0] * dC[k][0] + grad[r][1] * dC[k][1] + grad[r][2] * dC[k][2];
            }
        }
    }
}

void tse_constraint_jacobians(const tse_geometry *g, const tse_real pose[6], const tse_real q[6],
                              tse_real Fp[6][6], tse_real M[3][2][2])
{
    tse_plate frame;
    tse_real C[3][3];
    tse_plate_frame(pose, &frame);
    tse_apex_from_frame(g, pose, &frame, C);
    tse_constraint_rows(g, pose, &frame, C, q, TSE_R(1.0), Fp, M);
}

tse_status tse_jacobian(const tse_geometry *g, const tse_real pose[6], const tse_real q[6],
                        tse_real J[6][6])
{
    for (int k = 0; k < 6; ++k)
        if (!isfinite(pose[k]) || !isfinite(q[k]))
            return TSE_INVALID;
    tse_real Fp[6][6], M[3][2][2];
    tse_constraint_jacobians(g, pose, q, Fp, M);
    for (int i = 0; i < 3; ++i) {
        const tse_real(*m)[2] = M[i];
        const tse_real det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
        if (!(tse_fabs(det) > TSE_R(0.0)))
            return TSE_SINGULAR;
        /* M ds + dF/dp dp = 0, so ds/dp = -M^-1 dF/dp. */
        for (int k = 0; k < 6; ++k) {
            const tse_real f1 = Fp[2 * i][k], f2 = Fp[2 * i + 1][k];
            J[2 * i][k] = -(m[1][1] * f1 - m[0][1] * f2) / det;
            J[2 * i + 1][k] = -(m[0][0] * f2 - m[1][0] * f1) / det;
        }
    }
    return TSE_OK;
}

/* One step of Gaussian elimination with partial pivoting on column k.  Called with constant k,
 * so that every loop has a fixed trip count and unrolls.  Returns the pivot (0 if singular). */
static inline tse_real eliminate_column(tse_real N[6][6], int k)
{
    int p = k;
    for (int i = k + 1; i < 6; ++i)
        if (tse_fabs(N[i][k]) > tse_fabs(N[p][k]))
            p = i;
    if (p != k) {
        for (int j = k; j < 6; ++j) {
            const tse_real t = N[k][j];
            N[k][j] = N[p][j];
            N[p][j] = -t; /* negating the row keeps the determinant's sign without a counter */
        }
    }
    const tse_real pivot = N[k][k];
    if (pivot == TSE_R(0.0))
        return pivot;
    const tse_real inv = TSE_R(1.0) / pivot;
    for (int i = k + 1; i < 6; ++i) {
        const tse_real f = N[i][k] * inv;
        for (int j = k + 1; j < 6; ++j)
            N[i][j] -= f * N[k][j];
    }
    return pivot;
}

tse_real tse_hadamard_ratio(const tse_real A[6][6])
{
    /* Rows normalised first: the ratio is then the plain determinant, and the product of the
     * raw norms cannot underflow in float. */
    tse_real N[6][6];
    for (int i = 0; i < 6; ++i) {
        tse_real n = TSE_R(0.0);
        for (int j = 0; j < 6; ++j)
            n += A[i][j] * A[i][j];
        if (!(n > TSE_R(0.0)))
            return TSE_R(0.0);
        const tse_real inv = TSE_R(1.0) / tse_sqrt(n);
        for (int j = 0; j < 6; ++j)
            N[i][j] = A[i][j] * inv;
    }
    /* Only the determinant is kept, so nothing is stored for a later solve. */
    const tse_real det = eliminate_column(N, 0) * eliminate_column(N, 1) * eliminate_column(N, 2) *
                         eliminate_column(N, 3) * eliminate_column(N, 4) * eliminate_column(N, 5);
    return tse_fabs(det);
}

void tse_singular_values(const tse_real A[6][6], tse_real sv[6])
{
    tse_real AtA[6][6];
    for (int i = 0; i < 6; ++i) {
        for (int j = 0; j < 6; ++j) {
            tse_real s = TSE_R(0.0);
            for (int k = 0; k < 6; ++k)
                s += A[k][i] * A[k][j];
            AtA[i][j] = s;
        }
    }
    tse_sym_eigen6(AtA, sv);
    for (int i = 0; i < 6; ++i)
        sv[i] = sv[i] > TSE_R(0.0) ? tse_sqrt(sv[i]) : TSE_R(0.0);
}
