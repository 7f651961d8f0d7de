#include "kin_internal.h"
#include "tse/fk.h"
#include "tse/ik.h"

enum { FK_MAX_ITER = 60 };

/* The Newton step dp of F(p, q) = 0 at pose p: dF/dp dp = -F, the same step as the 6x6 system
 * of tse_constraint_rows would give, solved through its structure instead of by elimination.
 *
 * With halved gradients g1 = B - A and g2 = C - A of F1 and F2 with respect to ball joint C_i,
 * the step moves C_i by dC_i with g1 . dC_i = -F1 / 2 and g2 . dC_i = -F2 / 2: any such dC_i is
 * x_i + lambda_i n_i, x_i the solution in the span of g1 and g2 (its 2x2 Gram system) and
 * n_i = g1 x g2.  The plate moves rigidly, so its three ball joints keep their distances to first
 * order: (dC_i - dC_j) . e_ij = 0 for the three pairs, e_ij = rho_i - rho_j (C_i - C_j over
 * r_top), three equations in the lambda_i (the matrix whose determinant type2_ratio divides by
 * the row norms: singular exactly where the 6x6 system is), solved by Cramer's rule.  The rigid
 * motion with these velocities is v = mean of the dC_i (the rho_i sum to zero) and, with the
 * ball joints on a circle of radius r_top about v in the plane normal to N,
 * sum rho_i x dC_i = (3 r_top / 2) (I + N N^T) w, so w = (2 / (3 r_top)) (S - N (N . S) / 2).
 * Then the angle rates: w = droll R e_x + dpitch (-sin yaw, cos yaw, 0) + dyaw e_z; turned by
 * -yaw about z it reads (cos pitch droll, dpitch, dyaw - sin pitch droll).
 * Returns the squared length of the step in metres (rotation counted as r_top per radian), not
 * finite when the system is singular. */
TSE_FMA_CLONES
static tse_real fk_step(const tse_geometry *g, const tse_real q[6], const tse_real p[6], tse_real dp[6])
{
    tse_pose_frame f;
    tse_pose_frame_of(p, &f);
    tse_real x[3][3], n[3][3];
    for (int i = 0; i < 3; ++i) {
        const tse_scissor_frame *sf = &g->sc[i];
        const tse_real s_a = q[2 * i], s_b = q[2 * i + 1];
        /* d = C - O_i; g2 = C - A and g1 = B - A (horizontal). */
        const tse_real d[3] = {p[0] + g->r_top * f.rho[i][0] - sf->o[0], p[1] + g->r_top * f.rho[i][1] - sf->o[1],
                               p[2] + g->r_top * f.rho[i][2]};
        const tse_real A[2] = {s_a * sf->a[0], s_a * sf->a[1]};
        const tse_real g1[2] = {s_b * sf->b[0] - A[0], s_b * sf->b[1] - A[1]};
        const tse_real g2[3] = {d[0] - A[0], d[1] - A[1], d[2]};
        /* F in the spec's polynomial form (kinematics.md), whose terms are of the size of the
         * slides times the ball joint's offsets: |AC|^2 - |BC|^2 as a difference of two squares
         * of the ball joint's distance would round on the scale of that distance squared. */
        const tse_real u = d[0] * sf->a[0] + d[1] * sf->a[1], v = d[0] * sf->b[0] + d[1] * sf->b[1];
        const tse_real rho2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        const tse_real pa = s_a * (s_a - TSE_R(2.0) * u);
        const tse_real G11 = g1[0] * g1[0] + g1[1] * g1[1]; /* w^2 */
        const tse_real G12 = g1[0] * g2[0] + g1[1] * g2[1];
        const tse_real G22 = pa + rho2;                    /* |AC|^2 */
        /* The targets are -F / 2. */
        const tse_real f1 = TSE_R(-0.5) * (pa - s_b * (s_b - TSE_R(2.0) * v));
        const tse_real f2 = TSE_R(-0.5) * ((pa + (rho2 - g->L2)) - g->g * G11);
        const tse_real inv = TSE_R(1.0) / (G11 * G22 - G12 * G12);
        const tse_real al = (G22 * f1 - G12 * f2) * inv, be = (G11 * f2 - G12 * f1) * inv;
        x[i][0] = al * g1[0] + be * g2[0];
        x[i][1] = al * g1[1] + be * g2[1];
        x[i][2] = be * g2[2];
        n[i][0] = g1[1] * g2[2];
        n[i][1] = -(g1[0] * g2[2]);
        n[i][2] = g1[0] * g2[1] - g1[1] * g2[0];
    }
    /* a_ij lambda_i - b_ij lambda_j = c_ij for the pairs 12, 13, 23. */
    tse_real e12[3], e13[3], e23[3];
    for (int k = 0; k < 3; ++k) {
        e12[k] = f.rho[0][k] - f.rho[1][k];
        e13[k] = f.rho[0][k] - f.rho[2][k];
        e23[k] = f.rho[1][k] - f.rho[2][k];
    }
#define DOT3(u, w) ((u)[0] * (w)[0] + (u)[1] * (w)[1] + (u)[2] * (w)[2])
    const tse_real a12 = DOT3(n[0], e12), b12 = DOT3(n[1], e12);
    const tse_real a13 = DOT3(n[0], e13), b13 = DOT3(n[2], e13);
    const tse_real a23 = DOT3(n[1], e23), b23 = DOT3(n[2], e23);
    const tse_real x1e12 = DOT3(x[0], e12), x2e12 = DOT3(x[1], e12);
    const tse_real x1e13 = DOT3(x[0], e13), x3e13 = DOT3(x[2], e13);
    const tse_real x2e23 = DOT3(x[1], e23), x3e23 = DOT3(x[2], e23);
#undef DOT3
    const tse_real c12 = x2e12 - x1e12, c13 = x3e13 - x1e13, c23 = x3e23 - x2e23;
    const tse_real invD = TSE_R(1.0) / (a12 * a23 * b13 - a13 * b12 * b23);
    const tse_real lam[3] = {(a23 * b13 * c12 - b12 * b23 * c13 + b12 * b13 * c23) * invD,
                             (a13 * b23 * c12 - a12 * b23 * c13 + a12 * b13 * c23) * invD,
                             (a13 * a23 * c12 - a12 * a23 * c13 + a13 * b12 * c23) * invD};
    tse_real v[3] = {TSE_R(0.0), TSE_R(0.0), TSE_R(0.0)}, S[3] = {TSE_R(0.0), TSE_R(0.0), TSE_R(0.0)};
    for (int i = 0; i < 3; ++i) {
        const tse_real *r = f.rho[i];
        const tse_real dC[3] = {x[i][0] + lam[i] * n[i][0], x[i][1] + lam[i] * n[i][1], x[i][2] + lam[i] * n[i][2]};
        for (int k = 0; k < 3; ++k)
            v[k] += dC[k];
        S[0] += r[1] * dC[2] - r[2] * dC[1];
        S[1] += r[2] * dC[0] - r[0] * dC[2];
        S[2] += r[0] * dC[1] - r[1] * dC[0];
    }
    const tse_real NS = TSE_R(0.5) * (f.N[0] * S[0] + f.N[1] * S[1] + f.N[2] * S[2]);
    const tse_real kw = (TSE_R(2.0) / TSE_R(3.0)) * g->inv_r_top;
    const tse_real w[3] = {kw * (S[0] - NS * f.N[0]), kw * (S[1] - NS * f.N[1]), kw * (S[2] - NS * f.N[2])};
    const tse_real droll = (f.cy * w[0] + f.sy * w[1]) / f.cp;
    for (int k = 0; k < 3; ++k)
        dp[k] = v[k] * (TSE_R(1.0) / TSE_R(3.0));
    dp[TSE_ROLL] = droll;
    dp[TSE_PITCH] = f.cy * w[1] - f.sy * w[0];
    dp[TSE_YAW] = w[2] + f.sp * droll;
    return dp[0] * dp[0] + dp[1] * dp[1] + dp[2] * dp[2] +
           g->r_top * g->r_top * (dp[3] * dp[3] + dp[4] * dp[4] + dp[5] * dp[5]);
}

static tse_status fail(tse_fk_result *out, tse_status st, int scissor)
{
    out->status = st;
    out->scissor = scissor;
    return st;
}

/* The pose is only an answer if the inverse kinematics takes it back to q, within `share` of the
 * verify tolerance 0.01 sqrt(eps) L: TSE_OK, or the IK's refusal, or TSE_UNREACHABLE when it
 * solves to other slides (q is on another sheet); sets out->q_error and, on a failure,
 * out->status and out->scissor. */
static tse_status verify(const tse_geometry *g, const tse_real q[6], const tse_real p[6], tse_real share,
                         tse_fk_result *out)
{
    tse_ik_result ik;
    tse_ik(g, p, q, &ik);
    tse_real err = TSE_R(0.0);
    int worst = 0;
    for (int k = 0; k < 6; ++k) {
        const tse_real e = tse_fabs(ik.q[k] - q[k]);
        if (!(e <= err)) {
            err = e;
            worst = k / 2 + 1;
        }
    }
    out->q_error = err;
    if (ik.status != TSE_OK)
        return fail(out, ik.status, ik.scissor);
    const tse_real verify_tol = share * TSE_R(0.01) * tse_sqrt(TSE_REAL_EPS) * g->p.L;
    if (!(err <= verify_tol))
        return fail(out, TSE_UNREACHABLE, worst);
    out->status = TSE_OK;
    out->scissor = 0;
    return TSE_OK;
}

tse_status tse_fk(const tse_geometry *g, const tse_real q[6], const tse_real seed_pose[6],
                  tse_fk_result *out)
{
    out->status = TSE_OK;
    out->scissor = 0;
    out->iterations = 0;
    out->q_error = (tse_real)NAN;
    const tse_real *seed = seed_pose ? seed_pose : g->home_pose;
    for (int k = 0; k < 6; ++k) {
        out->pose[k] = seed[k];
        if (!isfinite(q[k]) || !isfinite(seed[k]))
            return fail(out, TSE_INVALID, 0);
    }
    /* Slides outside the stroke have no accepted pose, whatever Newton would make of them; said
     * before solving, since that search can end anywhere (no pose at all, or one the check then
     * refuses for another reason). */
    for (int k = 0; k < 6; ++k)
        if (!(q[k] >= g->p.s_min && q[k] <= g->p.s_max))
            return fail(out, TSE_STROKE, k / 2 + 1);
    /* Far from zero an angle is coarse (a float step is 1.2e-4 rad at 2000 rad, 2.5e-5 m of
     * ball-joint travel): Newton could not place the plate as finely as the slides need, and the
     * check below would pass a pose up to its tolerance off.  Same orientation, fine angles. */
    for (int k = TSE_ROLL; k <= TSE_YAW; ++k) {
        if (tse_fabs(out->pose[k]) > TSE_R(2.0) * TSE_PI) {
            tse_real s, c;
            tse_sincos(out->pose[k], &s, &c);
            out->pose[k] = tse_atan2(s, c);
        }
    }

    /* After a step n below 0.1 sqrt(eps) L the quadratic error left is below what the precision
     * resolves; or, as in the per-scissor Newton (scissor_core.h), once two successive steps in
     * the quadratic regime (the previous one below 1e-3 L) predict an error n_k^3 / n_{k-1}^2
     * below 1e-4 sqrt(eps) L: a warm seed then needs two steps, not three.  The check by the
     * inverse kinematics below stands behind either. */
    const tse_real tol2 = TSE_R(0.01) * TSE_REAL_EPS * g->L2;
    const tse_real max_move = TSE_R(0.1) * g->p.L;
    tse_real *p = out->pose, prev2 = TSE_R(0.0), start[6];
    for (int k = 0; k < 6; ++k)
        start[k] = p[k];
    int converged = 0;
    for (int it = 1; it <= FK_MAX_ITER && !converged; ++it) {
        tse_real dp[6];
        const tse_real n2 = fk_step(g, q, p, dp);
        if (!(n2 < (tse_real)INFINITY))
            break;
        const tse_real scale = n2 > max_move * max_move ? max_move / tse_sqrt(n2) : TSE_R(1.0);
        for (int k = 0; k < 6; ++k)
            p[k] += scale * dp[k];
        out->iterations = it;
        converged = n2 <= tol2 || (TSE_R(16.0) * n2 <= prev2 && prev2 <= g->newton_regime2 &&
                                   n2 * n2 * n2 <= g->newton_acc2 * prev2 * prev2);
        prev2 = n2;
    }
    tse_status st = converged ? verify(g, q, p, TSE_R(1.0), out) : TSE_NOCONVERGE;
    if (st == TSE_OK)
        return TSE_OK;
    /* Near a type-2 singularity the plate moves with the slides nearly held, and a float Newton
     * started on an answer can step off it, onto a pose that fails (the kin fuzz target's hour:
     * roll = pitch = -0.83 rad, 1.3e-4 rad off, degenerate).  The seed, if it is itself an answer,
     * is then the one nearest the seed: if it is one as Newton's would be, its slides as close to q
     * as the inverse kinematics' own accuracy.  The verify tolerance (6.0e-6 m in float at the
     * prototype's L) is looser than that (2e-6 m), since Newton's answer, exact but for rounding,
     * is checked only for its sheet; a quarter of it is inside the accuracy in either precision
     * (the kin fuzz target's hour: a float seed at roll = pitch = -pi, 2.8e-6 m off, taken). */
    const tse_status first = st;
    const int first_scissor = out->scissor;
    const tse_real first_err = out->q_error;
    tse_real tried[6];
    for (int k = 0; k < 6; ++k) {
        tried[k] = p[k];
        p[k] = start[k];
    }
    if (verify(g, q, p, TSE_R(0.25), out) == TSE_OK)
        return TSE_OK;
    for (int k = 0; k < 6; ++k)
        p[k] = tried[k];
    out->q_error = first == TSE_NOCONVERGE ? (tse_real)NAN : first_err;
    return fail(out, first, first == TSE_NOCONVERGE ? 0 : first_scissor);
}
