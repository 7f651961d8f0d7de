/* Forward kinematics (kinematics.md, "Forward kinematics"): FK(IK(p)) = p, failure rather than a
 * wrong pose, invalid input. */
#include "test_common.h"

static const double PI = 3.14159265358979323846;

/* J = dq/dp of the reference at (p, q), rotation columns per radian: J_i = -M_i^-1 dF_i/dp. */
static void orc_jacobian(const orc_geom *og, const orc_real pose[6], const orc_real q[6],
                         orc_real J[6][6])
{
    orc_real Fp[6][6], C[3][3];
    orc_constraint_jacobian(og, pose, q, Fp);
    orc_joints(og, pose, C);
    for (int i = 0; i < 3; i++) {
        orc_real F[2], M[2][2];
        orc_residual(og, i, C[i], q[2 * i], q[2 * i + 1], F, M);
        orc_real det = M[0][0] * M[1][1] - M[0][1] * M[1][0];
        for (int col = 0; col < 6; col++) {
            orc_real scale = col >= 3 ? og->r_top : 1.0L; /* undo the 1/r_top weighting */
            orc_real f0 = Fp[2 * i][col] * scale, f1 = Fp[2 * i + 1][col] * scale;
            J[2 * i][col] = -(M[1][1] * f0 - M[0][1] * f1) / det;
            J[2 * i + 1][col] = -(-M[1][0] * f0 + M[0][0] * f1) / det;
        }
    }
}

/* Row 1-norms of J^-1 (Gauss-Jordan, partial pivoting): |dp_k| <= norm_k max|dq|. */
static int inverse_row_norms(const orc_real J[6][6], orc_real norms[6])
{
    orc_real A[6][12];
    for (int i = 0; i < 6; i++)
        for (int j = 0; j < 12; j++)
            A[i][j] = j < 6 ? J[i][j] : (j - 6 == i ? 1.0L : 0.0L);
    for (int k = 0; k < 6; k++) {
        int piv = k;
        for (int i = k + 1; i < 6; i++)
            if (fabsl(A[i][k]) > fabsl(A[piv][k]))
                piv = i;
        if (A[piv][k] == 0.0L)
            return 0;
        for (int j = 0; j < 12; j++) {
            orc_real t = A[k][j];
            A[k][j] = A[piv][j];
            A[piv][j] = t;
        }
        orc_real d = A[k][k];
        for (int j = 0; j < 12; j++)
            A[k][j] /= d;
        for (int i = 0; i < 6; i++)
            if (i != k) {
                orc_real f = A[i][k];
                for (int j = 0; j < 12; j++)
                    A[i][j] -= f * A[k][j];
            }
    }
    for (int i = 0; i < 6; i++) {
        norms[i] = 0;
        for (int j = 0; j < 6; j++)
            norms[i] += fabsl(A[i][6 + j]);
    }
    return 1;
}

static void random_pose(uint64_t *seed, double r_max, double z_lo, double z_hi, double tilt,
                        double yaw, tse_real pose[6])
{
    double r = r_max * sqrt(rng_unit(seed)), ph = rng_range(seed, -PI, PI);
    set_pose(pose, r * cos(ph), r * sin(ph), rng_range(seed, z_lo, z_hi),
             rng_range(seed, -tilt, tilt), rng_range(seed, -tilt, tilt),
             rng_range(seed, -yaw, yaw));
}

/* A pose the library accepts, well away from both singularities. */
static int healthy_pose(const tse_geometry *g, const orc_geom *og, const tse_real pose[6],
                        tse_ik_result *r, orc_result *o)
{
    orc_tol tol = test_orc_tol();
    if (tse_ik(g, pose, NULL, r) != TSE_OK)
        return 0;
    orc_real po[6];
    pose_to_orc(pose, po);
    orc_ik(og, po, NULL, &tol, o);
    return o->status == TSE_OK && !o->ambiguous && !o->multi && o->mu[0] >= 0.1L &&
           o->mu[1] >= 0.1L && o->mu[2] >= 0.1L && o->nu >= 0.01L;
}

/* Per-component bound on |FK(IK(p)) - p| (see test_fk_of_ik_seeded). */
static void fk_bounds(const orc_geom *og, const tse_real pose[6], const tse_real q[6],
                      double bound[6])
{
    orc_real po[6], qo[6], J[6][6], norms[6];
    pose_to_orc(pose, po);
    q_to_orc(q, qo);
    orc_jacobian(og, po, qo, J);
    assert_true(inverse_row_norms(J, norms));
    for (int k = 0; k < 6; k++)
        bound[k] = IS_FLOAT ? 2.0 * (double)norms[k] * 4e-6 + 1e-7 : 1e-9;
}

/* In double: within 1e-9.  In float: q = IK_float(p) is within 2e-6 m of the exact slides, and
 * FK in float meets the constraints only to the same rounding (its residuals are evaluated in
 * float on the same terms), so the pose it returns differs from p by J^-1 applied to a slide
 * error of up to 2 x 2e-6 m: per component |dp_k| <= |row k of J^-1|_1 4e-6, doubled for margin.
 * The bound is computed per pose from the reference Jacobian. */
static void test_fk_of_ik_seeded(void **state)
{
    (void)state;
    tse_geometry g;
    orc_geom og;
    test_default_geometries(&g, &og);
    uint64_t seed = 31337;
    int tested = 0;
    double worst_ratio = 0, worst_bound = 0, worst_err = 0;
    for (int n = 0; n < 3000 && tested < 1500; n++) {
        tse_real pose[6];
        random_pose(&seed, 0.4, 0.4, 1.55, 0.3, 0.7, pose);
        tse_ik_result r;
        orc_result o;
        if (!healthy_pose(&g, &og, pose, &r, &o))
            continue;
        double bounds[6];
        fk_bounds(&og, pose, r.q, bounds);
        tse_real seed_pose[6];
        for (int k = 0; k < 6; k++)
            seed_pose[k] = pose[k] + (tse_real)(rng_range(&seed, -1, 1) * (k < 3 ? 2e-3 : 4e-3));
        tse_fk_result f;
        tse_status st = tse_fk(&g, r.q, seed_pose, &f);
        assert_int_equal(st, f.status);
        if (st != TSE_OK) {
            print_error("FK of IK(" POSE_FMT ") failed: %s/%d\n", POSE_ARGS(pose), st_name(st),
                        f.scissor);
            fail();
        }
        assert_int_equal(f.scissor, 0);
        for (int k = 0; k < 6; k++) {
            double bound = bounds[k];
            double err = fabs((double)f.pose[k] - (double)pose[k]);
            if (err / bound > worst_ratio) {
                worst_ratio = err / bound;
                worst_bound = bound;
                worst_err = err;
            }
            if (!(err <= bound)) {
                print_error("FK(IK(" POSE_FMT "))[%d] = %.17g, error %.3g > bound %.3g\n",
                            POSE_ARGS(pose), k, (double)f.pose[k], err, bound);
                fail();
            }
        }
        assert_true(f.q_error >= 0 && f.q_error <= (IS_FLOAT ? 1e-5 : 1e-9));
        tested++;
    }
    print_message("FK(IK(p)) seeded near p: %d poses, worst error %.3g (bound there %.3g)\n",
                  tested, worst_err, worst_bound);
    assert_true(tested >= 1000);
}

/* From home (no seed): moderate poses converge to p. */
static void test_fk_of_ik_from_home(void **state)
{
    (void)state;
    tse_geometry g;
    orc_geom og;
    test_default_geometries(&g, &og);
    uint64_t seed = 4711;
    int tested = 0;
    for (int n = 0; n < 2000 && tested < 500; n++) {
        tse_real pose[6];
        random_pose(&seed, 0.2, 0.6, 1.3, 0.15, 0.3, pose);
        tse_ik_result r;
        orc_result o;
        if (!healthy_pose(&g, &og, pose, &r, &o))
            continue;
        tse_fk_result f;
        tse_status st = tse_fk(&g, r.q, NULL, &f);
        if (st != TSE_OK) {
            print_error("FK from home of IK(" POSE_FMT ") failed: %s/%d\n", POSE_ARGS(pose),
                        st_name(st), f.scissor);
            fail();
        }
        double bounds[6];
        fk_bounds(&og, pose, r.q, bounds);
        for (int k = 0; k < 6; k++)
            EXPECT_NEAR(f.pose[k], pose[k], bounds[k]);
        tested++;
    }
    print_message("FK(IK(p)) from home: %d poses\n", tested);
    assert_true(tested >= 300);
}

/* Far from home and unseeded, FK may fail; when it answers, the answer must be a pose whose
 * solution is q (checked with the reference), never a wrong pose. */
static void test_fk_never_wrong(void **state)
{
    (void)state;
    tse_geometry g;
    orc_geom og;
    test_default_geometries(&g, &og);
    orc_tol tol = test_orc_tol();
    uint64_t seed = 5150;
    int ok_same = 0, ok_other = 0, failed = 0;
    for (int n = 0; n < 3000; n++) {
        tse_real pose[6];
        random_pose(&seed, 0.6, 0.3, 1.65, 0.7, 1.5, pose);
        tse_ik_result r;
        if (tse_ik(&g, pose, NULL, &r) != TSE_OK)
            continue;
        tse_fk_result f;
        tse_status st = tse_fk(&g, r.q, NULL, &f);
        if (st != TSE_OK) {
            failed++;
            continue;
        }
        int same = 1;
        for (int k = 0; k < 6; k++)
            if (!(fabs((double)f.pose[k] - (double)pose[k]) <= (IS_FLOAT ? 1e-3 : 1e-7)))
                same = 0;
        if (same) {
            ok_same++;
            continue;
        }
        /* another assembly of the same slides: the reference must agree it is one */
        ok_other++;
        if (ok_other <= 3)
            print_message("  q of " POSE_FMT "\n  also solved by " POSE_FMT "\n", POSE_ARGS(pose),
                          POSE_ARGS(f.pose));
        orc_real po[6], qo[6];
        pose_to_orc(f.pose, po);
        q_to_orc(r.q, qo);
        orc_result o;
        orc_ik(&og, po, qo, &tol, &o);
        if (o.status != TSE_OK && !o.ambiguous) {
            print_error("FK returned " POSE_FMT " for q of " POSE_FMT
                        ", which the reference rejects as %s/%d\n",
                        POSE_ARGS(f.pose), POSE_ARGS(pose), st_name(o.status), o.scissor);
            fail();
        }
        for (int k = 0; k < 6; k++)
            EXPECT_NEAR(o.q[k], r.q[k], IS_FLOAT ? 1e-5 : 1e-8);
    }
    print_message("FK from home on wide poses: %d found p, %d another assembly, %d failed\n",
                  ok_same, ok_other, failed);
}

/* Slides that no valid pose has: FK reports failure. */
static void test_fk_no_pose(void **state)
{
    (void)state;
    tse_geometry g;
    orc_geom og;
    test_default_geometries(&g, &og);
    /* w = sqrt(sA^2 + sB^2 + sA sB) (c = 1/2) > 2 l0 = 0.914: no real apex at all */
    const double impossible[][6] = {
        {0.9, 0.9, 0.0, 0.0, 0.9, 0.0},
        {0.9, 0.9, 0.9, 0.9, 0.9, 0.9},
        {0.0, 0.0, 0.9, 0.9, 0.0, 0.0},
        /* w = 0.9 on every scissor: alpha = acos(0.9/0.914) = 10.1 deg < alpha_min = 10.8 deg */
        {0.0, 0.9, 0.9, 0.0, 0.0, 0.9},
        /* zero width: alpha = 90 deg > alpha_max */
        {0.0, 0.0, 0.0, 0.0, 0.0, 0.0},
        /* one scissor closed, the others wide open */
        {0.0, 0.0, 0.9, 0.0, 0.0, 0.9},
    };
    for (size_t n = 0; n < sizeof impossible / sizeof impossible[0]; n++) {
        tse_real q[6];
        for (int k = 0; k < 6; k++)
            q[k] = (tse_real)impossible[n][k];
        for (int with_seed = 0; with_seed < 2; with_seed++) {
            tse_fk_result f;
            tse_status st = tse_fk(&g, q, with_seed ? g.home_pose : NULL, &f);
            assert_int_equal(st, f.status);
            if (st == TSE_OK) {
                print_error("FK of impossible q #%zu returned pose " POSE_FMT "\n", n,
                            POSE_ARGS(f.pose));
                fail();
            }
        }
    }
}

/* Slides outside the stroke (kinematics.md: 0 <= s <= 0.90 m for the prototype): no valid pose
 * has them, and FK says stroke, naming the scissor of the first such slide, before it solves
 * anything, whether or not a pose would exist and with or without a seed. */
static void test_fk_outside_stroke(void **state)
{
    (void)state;
    tse_geometry g;
    orc_geom og;
    test_default_geometries(&g, &og);
    const double worked = 0.43015083911167; /* all six slides at p = (0, 0, 1) */
    const double outside[] = {0.901, 1.0, 5.0, -1e-3, -0.5};
    for (int k = 0; k < 6; k++)
        for (size_t b = 0; b < sizeof outside / sizeof outside[0]; b++)
            for (int with_seed = 0; with_seed < 2; with_seed++) {
                tse_real q[6];
                for (int j = 0; j < 6; j++)
                    q[j] = (tse_real)worked;
                q[k] = (tse_real)outside[b];
                tse_fk_result f;
                EXPECT_STATUS(tse_fk(&g, q, with_seed ? g.home_pose : NULL, &f), TSE_STROKE);
                EXPECT_STATUS(f.status, TSE_STROKE);
                assert_int_equal(f.scissor, k / 2 + 1);
            }
    /* All six out: the first scissor is named. */
    const tse_real all[6] = {TSE_R(1.0), TSE_R(1.0), TSE_R(1.0), TSE_R(1.0), TSE_R(1.0), TSE_R(1.0)};
    tse_fk_result f;
    EXPECT_STATUS(tse_fk(&g, all, NULL, &f), TSE_STROKE);
    assert_int_equal(f.scissor, 1);
    /* A real pose beyond a shortened stroke: the worked slides with s_max = 0.40 m (scissor 1 is
     * the first), and within s_max = 0.45 m they solve to (0, 0, 1). */
    tse_params p;
    tse_params_default(&p);
    p.s_max = TSE_R(0.40);
    tse_geometry shorter;
    assert_int_equal(tse_geometry_init(&shorter, &p), TSE_PARAM_OK);
    tse_real q[6];
    for (int j = 0; j < 6; j++)
        q[j] = (tse_real)worked;
    EXPECT_STATUS(tse_fk(&shorter, q, NULL, &f), TSE_STROKE);
    assert_int_equal(f.scissor, 1);
    p.s_max = TSE_R(0.45);
    assert_int_equal(tse_geometry_init(&shorter, &p), TSE_PARAM_OK);
    EXPECT_STATUS(tse_fk(&shorter, q, NULL, &f), TSE_OK);
    EXPECT_NEAR(f.pose[TSE_Z], 1.0, IS_FLOAT ? 1e-4 : 1e-9);
    /* Non-finite comes first: invalid, not stroke. */
    q[0] = (tse_real)5.0;
    q[5] = (tse_real)NAN;
    EXPECT_STATUS(tse_fk(&g, q, NULL, &f), TSE_INVALID);
}

static void test_fk_invalid(void **state)
{
    (void)state;
    tse_geometry g;
    orc_geom og;
    test_default_geometries(&g, &og);
    const double bad[3] = {NAN, INFINITY, -INFINITY};
    for (int k = 0; k < 6; k++)
        for (int b = 0; b < 3; b++) {
            tse_real q[6];
            for (int j = 0; j < 6; j++)
                q[j] = (tse_real)0.43015083911167;
            q[k] = (tse_real)bad[b];
            tse_fk_result f;
            EXPECT_STATUS(tse_fk(&g, q, NULL, &f), TSE_INVALID);
            EXPECT_STATUS(f.status, TSE_INVALID);
            EXPECT_STATUS(tse_fk(&g, q, g.home_pose, &f), TSE_INVALID);
        }
    /* a non-finite seed: rejected, or ignored and the right answer */
    tse_real q[6], seed_pose[6];
    for (int j = 0; j < 6; j++)
        q[j] = (tse_real)0.43015083911167;
    for (int k = 0; k < 6; k++) {
        memcpy(seed_pose, g.home_pose, sizeof seed_pose);
        seed_pose[k] = (tse_real)NAN;
        tse_fk_result f;
        tse_status st = tse_fk(&g, q, seed_pose, &f);
        if (st != TSE_INVALID) {
            EXPECT_STATUS(st, TSE_OK);
            EXPECT_NEAR(f.pose[TSE_Z], 1.0, IS_FLOAT ? 1e-4 : 1e-9);
        }
    }
    /* the worked value backwards */
    tse_fk_result f;
    EXPECT_STATUS(tse_fk(&g, q, NULL, &f), TSE_OK);
    const double want[6] = {0, 0, 1.0, 0, 0, 0};
    for (int k = 0; k < 6; k++)
        EXPECT_NEAR(f.pose[k], want[k], IS_FLOAT ? 2e-5 : 1e-12);
    const double q2[6] = {0.39127069075903, 0.41631844093909, 0.38241559603276,
                          0.42099161248302, 0.56558364785006, 0.23697220292616};
    const double p2[6] = {0.1, -0.05, 1.1, 0.1, -0.05, 0.2};
    for (int k = 0; k < 6; k++)
        q[k] = (tse_real)q2[k];
    EXPECT_STATUS(tse_fk(&g, q, NULL, &f), TSE_OK);
    /* the 14-digit q carries 5e-15 m of rounding: the pose is good to ~1e-13 */
    for (int k = 0; k < 6; k++)
        EXPECT_NEAR(f.pose[k], p2[k], IS_FLOAT ? 1e-4 : 1e-11);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fk_invalid),
        cmocka_unit_test(test_fk_no_pose),
        cmocka_unit_test(test_fk_outside_stroke),
        cmocka_unit_test(test_fk_of_ik_seeded),
        cmocka_unit_test(test_fk_of_ik_from_home),
        cmocka_unit_test(test_fk_never_wrong),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
