/* Differential kinematics: the analytic Jacobian against differences of the IK and against the
 * reference, the constraint Jacobians, singular values and the Hadamard ratio on matrices built by
 * hand. */
#include "test_common.h"

static const double PI = 3.14159265358979323846;

static void random_pose(uint64_t *seed, tse_real pose[6])
{
    double r = 0.4 * sqrt(rng_unit(seed)), ph = rng_range(seed, -PI, PI);
    set_pose(pose, r * cos(ph), r * sin(ph), rng_range(seed, 0.4, 1.55),
             rng_range(seed, -0.3, 0.3), rng_range(seed, -0.3, 0.3), rng_range(seed, -0.7, 0.7));
}

static int healthy(const tse_geometry *g, const orc_geom *og, const tse_real pose[6],
                   tse_ik_result *r, orc_result *o)
{
    orc_tol tol = test_orc_tol();
    if (tse_ik(g, pose, NULL, r) != TSE_OK)
        return 0;
    orc_real po[6];
    pose_to_orc(pose, po);
    orc_ik(og, po, NULL, &tol, o);
    return o->status == TSE_OK && !o->multi && o->mu[0] >= 0.1L && o->mu[1] >= 0.1L &&
           o->mu[2] >= 0.1L;
}

/* Reference dq/dp: implicit differentiation of F(p, q) = 0 in long double. */
static void ref_jacobian(const orc_geom *og, const orc_real pose[6], const orc_real q[6],
                         orc_real J[6][6], orc_real Fp_unscaled[6][6], orc_real M[3][2][2])
{
    orc_real Fp[6][6], C[3][3];
    orc_constraint_jacobian(og, pose, q, Fp);
    orc_joints(og, pose, C);
    for (int i = 0; i < 3; i++) {
        orc_real F[2];
        orc_residual(og, i, C[i], q[2 * i], q[2 * i + 1], F, M[i]);
        orc_real det = M[i][0][0] * M[i][1][1] - M[i][0][1] * M[i][1][0];
        for (int col = 0; col < 6; col++) {
            orc_real scale = col >= 3 ? og->r_top : 1.0L;
            orc_real f0 = Fp[2 * i][col] * scale, f1 = Fp[2 * i + 1][col] * scale;
            Fp_unscaled[2 * i][col] = f0;
            Fp_unscaled[2 * i + 1][col] = f1;
            J[2 * i][col] = -(M[i][1][1] * f0 - M[i][0][1] * f1) / det;
            J[2 * i + 1][col] = -(-M[i][1][0] * f0 + M[i][0][0] * f1) / det;
        }
    }
}

/* tse_jacobian against the reference's implicit differentiation (both precisions) and, in double,
 * against central differences of the library's own IK with a step of 1e-6. */
static void test_jacobian_analytic(void **state)
{
    (void)state;
    tse_geometry g;
    orc_geom og;
    test_default_geometries(&g, &og);
    uint64_t seed = 2718;
    int tested = 0;
    double worst_ref = 0, worst_fd = 0;
    for (int n = 0; n < 1000 && tested < 300; n++) {
        tse_real pose[6];
        random_pose(&seed, pose);
        tse_ik_result r;
        orc_result o;
        if (!healthy(&g, &og, pose, &r, &o))
            continue;
        tse_real J[6][6];
        EXPECT_STATUS(tse_jacobian(&g, pose, r.q, J), TSE_OK);
        orc_real po[6], Jr[6][6], Fu[6][6], M[3][2][2];
        pose_to_orc(pose, po);
        ref_jacobian(&og, po, o.q, Jr, Fu, M);
        double jmax = 0;
        for (int i = 0; i < 6; i++)
            for (int j = 0; j < 6; j++)
                if (fabs((double)Jr[i][j]) > jmax)
                    jmax = fabs((double)Jr[i][j]);
        /* float: J is built from float q and float M; relative error a few 1e-6 of |J| at
         * mu >= 0.1, where M^-1 is at most ~10 times worse conditioned than at best */
        double tol_ref = (IS_FLOAT ? 2e-4 : 1e-10) * (1.0 + jmax);
        for (int i = 0; i < 6; i++)
            for (int j = 0; j < 6; j++) {
                double e = fabs((double)J[i][j] - (double)Jr[i][j]);
                if (e / (1.0 + jmax) > worst_ref)
                    worst_ref = e / (1.0 + jmax);
                if (!(e <= tol_ref)) {
                    print_error("pose " POSE_FMT ": J[%d][%d] = %.12g, reference %.12Lg\n",
                                POSE_ARGS(pose), i, j, (double)J[i][j], Jr[i][j]);
                    fail();
                }
            }
#if !TSE_REAL_FLOAT
        /* central differences of the IK, warm-started at q so the branch is the same */
        const double h = 1e-6;
        for (int j = 0; j < 6; j++) {
            tse_real pp[6], pm[6];
            memcpy(pp, pose, sizeof pp);
            memcpy(pm, pose, sizeof pm);
            pp[j] += h;
            pm[j] -= h;
            tse_ik_result rp, rm;
            tse_ik(&g, pp, r.q, &rp);
            tse_ik(&g, pm, r.q, &rm);
            assert_true(all_finite_q(rp.q) && all_finite_q(rm.q));
            for (int i = 0; i < 6; i++) {
                double fd = (rp.q[i] - rm.q[i]) / (2 * h);
                /* truncation ~h^2 |q'''|, rounding ~1e-12/h of the IK's accuracy */
                double e = fabs(fd - J[i][j]);
                if (e / (1.0 + jmax) > worst_fd)
                    worst_fd = e / (1.0 + jmax);
                if (!(e <= 1e-5 * (1.0 + jmax))) {
                    print_error("pose " POSE_FMT ": J[%d][%d] = %.12g, central difference %.12g\n",
                                POSE_ARGS(pose), i, j, (double)J[i][j], fd);
                    fail();
                }
            }
        }
#endif
        tested++;
    }
    print_message("Jacobian: %d poses, worst error relative to 1 + max|J|: %.3g against the "
                  "reference",
                  tested, worst_ref);
    if (!IS_FLOAT)
        print_message(", %.3g against central differences of the IK", worst_fd);
    print_message("\n");
    assert_true(tested >= 200);
}

/* The constraint Jacobians: M_i and the translation columns of dF/dp exactly as the reference;
 * the rotation columns are dF/d(roll, pitch, yaw), either per radian or weighed by 1/r_top as
 * kinematics.md weighs them for nu.  Its Hadamard ratio, so weighed, is nu. */
static void test_constraint_jacobians(void **state)
{
    (void)state;
    tse_geometry g;
    orc_geom og;
    test_default_geometries(&g, &og);
    uint64_t seed = 161;
    int tested = 0, per_radian = 0, weighed = 0;
    for (int n = 0; n < 400 && tested < 100; n++) {
        tse_real pose[6];
        random_pose(&seed, pose);
        tse_ik_result r;
        orc_result o;
        if (!healthy(&g, &og, pose, &r, &o))
            continue;
        tse_real Fp[6][6], M[3][2][2];
        tse_constraint_jacobians(&g, pose, r.q, Fp, M);
        orc_real po[6], qo[6], Jr[6][6], Fu[6][6], Mr[3][2][2];
        pose_to_orc(pose, po);
        q_to_orc(r.q, qo);
        ref_jacobian(&og, po, qo, Jr, Fu, Mr);
        double e = IS_FLOAT ? 2e-5 : 1e-12;
        for (int i = 0; i < 3; i++)
            for (int a = 0; a < 2; a++)
                for (int b = 0; b < 2; b++)
                    EXPECT_NEAR(M[i][a][b], Mr[i][a][b], e);
        for (int i = 0; i < 6; i++)
            for (int j = 0; j < 3; j++)
                EXPECT_NEAR(Fp[i][j], Fu[i][j], e);
        int is_rad = 1, is_weighed = 1;
        for (int i = 0; i < 6; i++)
            for (int j = 3; j < 6; j++) {
                if (!(fabs((double)Fp[i][j] - (double)Fu[i][j]) <= e))
                    is_rad = 0;
                if (!(fabs((double)Fp[i][j] - (double)(Fu[i][j] / og.r_top)) <= e / 0.2))
                    is_weighed = 0;
            }
        if (!is_rad && !is_weighed) {
            print_error("pose " POSE_FMT ": rotation columns of dF/dp match neither dF/dangle "
                        "nor dF/dangle / r_top; row 0: %.9g %.9g %.9g, reference %.9Lg %.9Lg "
                        "%.9Lg\n",
                        POSE_ARGS(pose), (double)Fp[0][3], (double)Fp[0][4], (double)Fp[0][5],
                        Fu[0][3], Fu[0][4], Fu[0][5]);
            fail();
        }
        per_radian += is_rad;
        weighed += is_weighed;
        /* nu of the IK is the Hadamard ratio of the weighed matrix */
        tse_real W[6][6];
        for (int i = 0; i < 6; i++)
            for (int j = 0; j < 6; j++)
                W[i][j] = (tse_real)(j < 3 ? Fu[i][j] : Fu[i][j] / og.r_top);
        EXPECT_NEAR(tse_hadamard_ratio(W), r.nu, IS_FLOAT ? 1e-4 : 1e-10);
        tested++;
    }
    print_message("dF/dp rotation columns: %d per radian, %d weighed by 1/r_top (of %d)\n",
                  per_radian, weighed, tested);
    assert_true(tested >= 50);
}

/* nu, which the IK takes from a closed form (kinematics/src/jacobian.c), is the Hadamard ratio of
 * dF/dp with its rotation columns weighed by 1/r_top, computed here by elimination on the rows of
 * tse_constraint_jacobians (checked against the reference above), over poses tilted far enough
 * (pitch to +-1.3 rad) that the plate's axes are far from orthogonal, and on both sides of nu_min. */
static void test_nu_matches_elimination(void **state)
{
    (void)state;
    tse_geometry g;
    orc_geom og;
    test_default_geometries(&g, &og);
    uint64_t seed = 4242;
    int ok = 0, degenerate = 0, steep = 0;
    double worst = 0;
    for (int n = 0; n < 200000 && (ok < 300 || degenerate < 30); n++) {
        tse_real pose[6];
        const double r = 0.5 * sqrt(rng_unit(&seed)), ph = rng_range(&seed, -PI, PI);
        set_pose(pose, r * cos(ph), r * sin(ph), rng_range(&seed, 0.3, 1.6),
                 rng_range(&seed, -1.3, 1.3), rng_range(&seed, -1.3, 1.3),
                 rng_range(&seed, -PI, PI));
        tse_ik_result res;
        const tse_status st = tse_ik(&g, pose, NULL, &res);
        if (st != TSE_OK && st != TSE_DEGENERATE)
            continue;
        tse_real Fp[6][6], M[3][2][2];
        tse_constraint_jacobians(&g, pose, res.q, Fp, M);
        for (int i = 0; i < 6; i++)
            for (int j = 3; j < 6; j++)
                Fp[i][j] /= g.r_top;
        const double want = (double)tse_hadamard_ratio(Fp);
        const double e = fabs((double)res.nu - want);
        if (e > worst)
            worst = e;
        if (!(e <= (IS_FLOAT ? 2e-5 : 1e-12))) {
            print_error("pose " POSE_FMT ": nu %.9g, elimination %.9g\n", POSE_ARGS(pose),
                        (double)res.nu, want);
            fail();
        }
        ok += st == TSE_OK;
        degenerate += st == TSE_DEGENERATE;
        steep += fabs((double)pose[TSE_PITCH]) > 0.8;
    }
    print_message("nu against elimination: %d ok, %d degenerate (%d with |pitch| > 0.8), worst "
                  "difference %.3g\n",
                  ok, degenerate, steep, worst);
    assert_true(ok >= 300 && degenerate >= 30 && steep >= 30);
}

static void test_jacobian_bad_input(void **state)
{
    (void)state;
    tse_geometry g;
    orc_geom og;
    test_default_geometries(&g, &og);
    tse_real pose[6], q[6], J[6][6];
    set_pose(pose, 0, 0, 1.0, 0, 0, 0);
    for (int k = 0; k < 6; k++)
        q[k] = (tse_real)0.43015083911167;
    EXPECT_STATUS(tse_jacobian(&g, pose, q, J), TSE_OK);
    for (int k = 0; k < 6; k++) {
        tse_real p2[6], q2[6];
        memcpy(p2, pose, sizeof p2);
        memcpy(q2, q, sizeof q2);
        p2[k] = (tse_real)NAN;
        EXPECT_STATUS(tse_jacobian(&g, p2, q, J), TSE_INVALID);
        q2[k] = (tse_real)INFINITY;
        EXPECT_STATUS(tse_jacobian(&g, pose, q2, J), TSE_INVALID);
    }
    /* On the vertical axis u = v = u0: with s_A1 = s_B1 = u0 the first row of M_1 vanishes
     * (s_A - u = s_B - v = 0 up to rounding), so M_1 is singular. */
    orc_real u0 = (og.r_top - og.r_act) * sinl(og.p.eta);
    q[0] = q[1] = (tse_real)u0;
    tse_status st = tse_jacobian(&g, pose, q, J);
    if (st != TSE_SINGULAR) {
        /* a rounding-level det M may slip through; then the derivatives must be enormous */
        double big = 0;
        for (int j = 0; j < 6; j++)
            if (fabs((double)J[0][j]) > big)
                big = fabs((double)J[0][j]);
        if (!(st == TSE_OK && big > 1e6) && st != TSE_SINGULAR) {
            print_error("singular M_1: status %s, max |J[0][*]| = %g\n", st_name(st), big);
            fail();
        }
    }
}

/* ---------------------------------------------------------------------------------------------
 * Matrices with known singular values: U diag(s) V^T with U, V products of Givens rotations. */

static void givens(double A[6][6], int i, int j, double th)
{
    /* A <- G A with G the rotation by th in the (i, j) plane */
    double c = cos(th), s = sin(th);
    for (int k = 0; k < 6; k++) {
        double a = A[i][k], b = A[j][k];
        A[i][k] = c * a - s * b;
        A[j][k] = s * a + c * b;
    }
}

static void random_orthogonal(uint64_t *seed, double Q[6][6])
{
    for (int i = 0; i < 6; i++)
        for (int j = 0; j < 6; j++)
            Q[i][j] = i == j ? 1.0 : 0.0;
    for (int rep = 0; rep < 3; rep++)
        for (int i = 0; i < 6; i++)
            for (int j = i + 1; j < 6; j++)
                givens(Q, i, j, rng_range(seed, -PI, PI));
}

static void build_usv(const double U[6][6], const double s[6], const double V[6][6],
                      tse_real A[6][6])
{
    for (int i = 0; i < 6; i++)
        for (int j = 0; j < 6; j++) {
            double sum = 0;
            for (int k = 0; k < 6; k++)
                sum += U[i][k] * s[k] * V[j][k];
            A[i][j] = (tse_real)sum;
        }
}

static void test_singular_values_known(void **state)
{
    (void)state;
    uint64_t seed = 6;
    const double sets[][6] = {
        {5.0, 3.0, 2.0, 1.0, 0.5, 0.1},
        {0.1, 2.0, 5.0, 0.5, 3.0, 1.0}, /* unsorted on the diagonal */
        {1, 1, 1, 1, 1, 1},
        {4.0, 4.0, 2.0, 2.0, 1.0, 1.0}, /* repeated */
        {3.0, 2.0, 1.0, 0.5, 0.25, 0.0}, /* rank 5 */
    };
    for (size_t n = 0; n < sizeof sets / sizeof sets[0]; n++) {
        for (int rep = 0; rep < 5; rep++) {
            double U[6][6], V[6][6];
            random_orthogonal(&seed, U);
            random_orthogonal(&seed, V);
            tse_real A[6][6];
            build_usv(U, sets[n], V, A);
            tse_real sv[6];
            tse_singular_values(A, sv);
            double sorted[6];
            memcpy(sorted, sets[n], sizeof sorted);
            for (int a = 0; a < 6; a++)
                for (int b = a + 1; b < 6; b++)
                    if (sorted[b] > sorted[a]) {
                        double t = sorted[a];
                        sorted[a] = sorted[b];
                        sorted[b] = t;
                    }
            for (int k = 0; k < 6; k++) {
                /* from the eigenvalues of A^T A: an absolute error of eps s_max^2 in the
                 * eigenvalue, i.e. eps s_max^2 / (2 s) in s, and sqrt(eps) s_max at s = 0 */
                double eps = IS_FLOAT ? 1.2e-7 : 2.2e-16;
                double tol = sorted[k] > 0 ? 50 * eps * 25 / (2 * sorted[k]) + 20 * eps * sorted[k]
                                           : 10 * sqrt(eps) * 5;
                EXPECT_NEAR(sv[k], sorted[k], tol);
                if (k > 0)
                    assert_true(sv[k] <= sv[k - 1]);
            }
        }
    }
    /* a permutation with signs: all singular values 1 */
    tse_real P[6][6];
    memset(P, 0, sizeof P);
    const int perm[6] = {3, 0, 5, 1, 4, 2};
    for (int i = 0; i < 6; i++)
        P[i][perm[i]] = (tse_real)(i % 2 ? -1 : 1);
    tse_real sv[6];
    tse_singular_values(P, sv);
    for (int k = 0; k < 6; k++)
        EXPECT_NEAR(sv[k], 1.0, IS_FLOAT ? 1e-6 : 1e-14);
    /* diagonal with negative entries */
    tse_real D[6][6];
    memset(D, 0, sizeof D);
    const double d[6] = {-2, 7, 0.5, -3, 1, -0.25};
    for (int i = 0; i < 6; i++)
        D[i][i] = (tse_real)d[i];
    tse_singular_values(D, sv);
    const double want[6] = {7, 3, 2, 1, 0.5, 0.25};
    for (int k = 0; k < 6; k++)
        EXPECT_NEAR(sv[k], want[k], IS_FLOAT ? 1e-5 : 1e-13);
}

static void test_hadamard_ratio_known(void **state)
{
    (void)state;
    uint64_t seed = 7;
    double e = IS_FLOAT ? 1e-5 : 1e-13;
    for (int rep = 0; rep < 10; rep++) {
        double Q[6][6];
        random_orthogonal(&seed, Q);
        tse_real A[6][6];
        for (int i = 0; i < 6; i++)
            for (int j = 0; j < 6; j++)
                A[i][j] = (tse_real)Q[i][j];
        EXPECT_NEAR(tse_hadamard_ratio(A), 1.0, e);
        /* rows scaled: still orthogonal rows */
        for (int i = 0; i < 6; i++)
            for (int j = 0; j < 6; j++)
                A[i][j] = (tse_real)(Q[i][j] * (i + 1) * 0.7);
        EXPECT_NEAR(tse_hadamard_ratio(A), 1.0, e);
        /* two equal rows: singular */
        for (int j = 0; j < 6; j++)
            A[4][j] = A[1][j];
        EXPECT_NEAR(tse_hadamard_ratio(A), 0.0, e);
        /* rank 5 by construction: a row is a combination of two others */
        for (int i = 0; i < 6; i++)
            for (int j = 0; j < 6; j++)
                A[i][j] = (tse_real)Q[i][j];
        for (int j = 0; j < 6; j++)
            A[5][j] = (tse_real)(0.3 * Q[0][j] - 1.7 * Q[2][j]);
        EXPECT_NEAR(tse_hadamard_ratio(A), 0.0, e);
    }
    /* unit upper triangular of ones: det 1, row norms sqrt(6), sqrt(5), ..., 1 */
    tse_real T[6][6];
    for (int i = 0; i < 6; i++)
        for (int j = 0; j < 6; j++)
            T[i][j] = (tse_real)(j >= i ? 1 : 0);
    EXPECT_NEAR(tse_hadamard_ratio(T), 1.0 / sqrt(720.0), e);
    /* a zero row */
    for (int j = 0; j < 6; j++)
        T[3][j] = 0;
    EXPECT_NEAR(tse_hadamard_ratio(T), 0.0, e);
    /* negative determinant counts by magnitude: a swap of two rows of the identity */
    tse_real S[6][6];
    memset(S, 0, sizeof S);
    for (int i = 0; i < 6; i++)
        S[i][i] = 1;
    S[0][0] = S[1][1] = 0;
    S[0][1] = S[1][0] = 1;
    EXPECT_NEAR(tse_hadamard_ratio(S), 1.0, e);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_jacobian_analytic),
        cmocka_unit_test(test_constraint_jacobians),
        cmocka_unit_test(test_nu_matches_elimination),
        cmocka_unit_test(test_jacobian_bad_input),
        cmocka_unit_test(test_singular_values_known),
        cmocka_unit_test(test_hadamard_ratio_known),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
