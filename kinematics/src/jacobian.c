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

/* |(g, rot_scale (axis_k . (rc x g))_k)|: the norm of a row of tse_constraint_rows with gradient g
 * (with respect to the ball joint) for a ball joint at rc from the plate's centre. */
static tse_real row_norm(const tse_plate *f, tse_real rot_scale, const tse_real rc[3], const tse_real gr[3])
{
    const tse_real p[3] = {rc[1] * gr[2] - rc[2] * gr[1], rc[2] * gr[0] - rc[0] * gr[2],
                           rc[0] * gr[1] - rc[1] * gr[0]};
    tse_real n = gr[0] * gr[0] + gr[1] * gr[1] + gr[2] * gr[2];
    for (int k = 0; k < 3; ++k) {
        const tse_real *ax = f->axes[k];
        const tse_real t = rot_scale * (ax[0] * p[0] + ax[1] * p[1] + ax[2] * p[2]);
        n += t * t;
    }
    return tse_sqrt(n);
}

/* The Hadamard ratio of Fp = tse_constraint_rows(rot_scale = s) without forming Fp.
 *
 * Row (i, r) of Fp is (g, s Ax (rc_i x g)) with g = dF_r/dC_i, rc_i = C_i - (X, Y, Z) and Ax the
 * matrix whose rows are the roll, pitch and yaw axes; so Fp = [G | P] diag(I, s Ax^T) with rows
 * (g, rc_i x g) in [G | P], and det Fp = s^3 det(Ax) det[G | P].  A row (g, rc x g) is the line
 * through the ball joint along g; [G | P] t = 0 for a twist t = (v, w) exactly when every ball
 * joint's velocity v + w x rc_i is normal to both of its gradients, i.e. along
 * n_i = g_{i,1} x g_{i,2}; a velocity field lambda_i n_i is rigid when
 * (lambda_i n_i - lambda_j n_j) . e_ij = 0 for the three pairs, e_ij = C_i - C_j.  det[G | P] is
 * linear in each n_i (alternating and bilinear in the two rows of a ball joint) and cubic in the
 * positions, like the determinant of that 3x3 system, and the two are equal up to sign:
 *
 *     det[G | P] = -( (n_1.e_12)(n_2.e_23)(n_3.e_13) - (n_2.e_12)(n_1.e_13)(n_3.e_23) )
 *
 * (checked in exact rational arithmetic on random lines, and against the 6x6 elimination of
 * tse_hadamard_ratio by the kinematics tests).  Dividing n_i by the norms of its two rows and
 * scaling e_ij by s gives the ratio directly, with every factor of order one (no overflow or
 * underflow of the raw product of norms).  A gradient may be scaled freely: the ratio does not
 * depend on a row's length, so the gradients are taken at half the size of constraint_rows. */
tse_real tse_type2_margin(const tse_geometry *g, const tse_real pose[6], const tse_plate *f,
                          const tse_real C[3][3], const tse_scissor_local loc[3], const tse_real q[6])
{
    const tse_real s = g->inv_r_top;
    tse_real n[3][3];
    for (int i = 0; i < 3; ++i) {
        const tse_scissor_frame *sf = &g->sc[i];
        const tse_real s_a = q[2 * i], s_b = q[2 * i + 1];
        /* F1 = |AC|^2 - |BC|^2 and F2 = |AC|^2 - ..., halved gradients as in constraint_rows. */
        tse_real g1[3], g2[3];
        for (int k = 0; k < 2; ++k) {
            g1[k] = s_b * sf->b[k] - s_a * sf->a[k];
            g2[k] = loc[i].d[k] - s_a * sf->a[k];
        }
        g1[2] = TSE_R(0.0);
        g2[2] = loc[i].d[2];
        const tse_real rc[3] = {C[i][0] - pose[0], C[i][1] - pose[1], C[i][2] - pose[2]};
        const tse_real norms = row_norm(f, s, rc, g1) * row_norm(f, s, rc, g2);
        /* A zero row makes Fp singular (tse_hadamard_ratio's convention). */
        if (!(norms > TSE_R(0.0)))
            return TSE_R(0.0);
        const tse_real k = TSE_R(1.0) / norms;
        n[i][0] = k * (g1[1] * g2[2] - g1[2] * g2[1]);
        n[i][1] = k * (g1[2] * g2[0] - g1[0] * g2[2]);
        n[i][2] = k * (g1[0] * g2[1] - g1[1] * g2[0]);
    }
    tse_real e12[3], e13[3], e23[3];
    for (int k = 0; k < 3; ++k) {
        e12[k] = s * (C[0][k] - C[1][k]);
        e13[k] = s * (C[0][k] - C[2][k]);
        e23[k] = s * (C[1][k] - C[2][k]);
    }
#define DOT3(x, y) ((x)[0] * (y)[0] + (x)[1] * (y)[1] + (x)[2] * (y)[2])
    const tse_real det_k = DOT3(n[0], e12) * DOT3(n[1], e23) * DOT3(n[2], e13) -
                           DOT3(n[1], e12) * DOT3(n[0], e13) * DOT3(n[2], e23);
#undef DOT3
    const tse_real(*ax)[3] = f->axes;
    const tse_real det_ax = ax[0][0] * (ax[1][1] * ax[2][2] - ax[1][2] * ax[2][1]) -
                            ax[0][1] * (ax[1][0] * ax[2][2] - ax[1][2] * ax[2][0]) +
                            ax[0][2] * (ax[1][0] * ax[2][1] - ax[1][1] * ax[2][0]);
    return tse_fabs(det_k * det_ax);
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
