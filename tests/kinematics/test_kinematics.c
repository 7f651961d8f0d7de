/* The kinematics contract, compiled once per precision (TSE_REAL_FLOAT).  Expectations come from
 * the spec's worked values, hand algebra and physical invariants. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>

#include "tse/fk.h"
#include "tse/ik.h"
#include "tse/jacobian.h"
#include "tse/metrics.h"

#if defined(TSE_REAL_FLOAT) && TSE_REAL_FLOAT
#define Q_TOL 2e-6   /* kinematics.md: single precision, where mu >= 0.1 */
#define POSE_TOL 2e-5 /* FK in float: residual ~1e-7 over a gain of ~1/10 per slide */
#else
#define Q_TOL 1e-10  /* 10 times inside the contract's 1e-9 m (the solver stops near 1e-11 m) */
#define POSE_TOL 1e-10
#endif

static tse_geometry G;
static tse_params P;

static int setup(void **state)
{
    (void)state;
    tse_params_default(&P);
    return tse_geometry_init(&G, &P) == TSE_PARAM_OK ? 0 : -1;
}

static double U(double a, double b) { return a + (b - a) * rand() / (double)RAND_MAX; }

static tse_status ik(const double p[6], tse_ik_result *r)
{
    tse_real pose[6];
    for (int k = 0; k < 6; ++k)
        pose[k] = (tse_real)p[k];
    return tse_ik(&G, pose, NULL, r);
}

static void test_defaults(void **state)
{
    (void)state;
    assert_true(fabs((double)P.L - 1.727) < 1e-6);
    assert_true(fabs((double)P.k1 - 0.2647) < 1e-6);
    assert_true(fabs((double)P.eta - M_PI / 6) < 1e-6);
    assert_true(fabs((double)P.alpha_min - asin(0.324 / 1.727)) < 1e-6);
    assert_true(fabs((double)P.alpha_max - asin(1.619 / 1.727)) < 1e-6);
    assert_true((double)P.s_min == 0.0 && fabs((double)P.s_max - 0.9) < 1e-6);
}

static void test_worked_values(void **state)
{
    (void)state;
    tse_ik_result r;
    const double home[6] = {0, 0, 1.0, 0, 0, 0};
    assert_int_equal(ik(home, &r), TSE_OK);
    assert_int_equal(r.scissor, 0);
    for (int k = 0; k < 6; ++k)
        assert_true(fabs((double)r.q[k] - 0.43015083911167) <= Q_TOL);
    const double p[6] = {0.1, -0.05, 1.1, 0.1, -0.05, 0.2};
    const double q[6] = {0.39127069075903, 0.41631844093909, 0.38241559603276,
                         0.42099161248302, 0.56558364785006, 0.23697220292616};
    assert_int_equal(ik(p, &r), TSE_OK);
    for (int k = 0; k < 6; ++k)
        assert_true(fabs((double)r.q[k] - q[k]) <= Q_TOL);
    for (int i = 0; i < 3; ++i)
        assert_true(r.mu[i] > 0 && r.mu[i] <= 1);
    assert_true(r.nu > 0 && r.nu <= 1);
}

/* On the vertical axis s_A = s_B = s satisfies F1, and F2 becomes, by hand,
 * s^2 (1 - 2g(1 + c)) - 2 u0 s + (rho2 - L^2) = 0, u0 = (r_top - r_act) sin(eta),
 * rho2 = (r_top - r_act)^2 + Z^2; the physical root is the larger one. */
static double vertical(double z)
{
    const double L = 1.727, l0 = 0.2647 * L, d = (0.11765 - 0.0186) * L, eta = M_PI / 6;
    const double g = (1 - (L / l0) * (L / l0)) / 4, c = cos(2 * eta);
    const double A = 1 - 2 * g * (1 + c), u0 = d * sin(eta), k = d * d + z * z - L * L;
    return (u0 + sqrt(u0 * u0 - A * k)) / A;
}

static void test_vertical_closed_form(void **state)
{
    (void)state;
    for (double z = 0.35; z < 1.6; z += 0.01) {
        const double pose[6] = {0, 0, z, 0, 0, 0};
        tse_ik_result r;
        assert_int_equal(ik(pose, &r), TSE_OK);
        for (int k = 0; k < 6; ++k)
            assert_true(fabs((double)r.q[k] - vertical(z)) <= Q_TOL);
        assert_true(fabs((double)tse_vertical_slide(&G, (tse_real)z) - vertical(z)) <= (Q_TOL > 1e-9 ? Q_TOL : 1e-13));
    }
}

static void test_symmetry(void **state)
{
    (void)state;
    srand(21);
    const double c = cos(2 * M_PI / 3), s = sin(2 * M_PI / 3);
    int compared = 0;
    for (int rep = 0; rep < 500; ++rep) {
        /* 120 degrees about Z: the position turns, yaw stays (R' = Rz R Rz^T = R for zero tilt). */
        const double p[6] = {U(-0.3, 0.3), U(-0.3, 0.3), U(0.4, 1.5), 0, 0, U(-0.5, 0.5)};
        const double pr[6] = {c * p[0] - s * p[1], s * p[0] + c * p[1], p[2], 0, 0, p[5]};
        tse_ik_result a, b;
        if (ik(p, &a) != TSE_OK)
            continue;
        assert_int_equal(ik(pr, &b), TSE_OK);
        /* Scissor i + 1 of the turned pose does what scissor i did. */
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 2; ++j)
                assert_true(fabs((double)b.q[2 * ((i + 1) % 3) + j] - (double)a.q[2 * i + j]) <= 10 * Q_TOL + 1e-12);
        /* Mirror in the XZ plane: Y, roll and yaw change sign; A and B swap, scissors 2 and 3 swap. */
        const double t[6] = {p[0], p[1], p[2], U(-0.2, 0.2), U(-0.2, 0.2), p[5]};
        const double m[6] = {t[0], -t[1], t[2], -t[3], t[4], -t[5]};
        if (ik(t, &a) != TSE_OK)
            continue;
        assert_int_equal(ik(m, &b), TSE_OK);
        const int map[6] = {1, 0, 5, 4, 3, 2};
        for (int k = 0; k < 6; ++k)
            assert_true(fabs((double)b.q[map[k]] - (double)a.q[k]) <= 10 * Q_TOL + 1e-12);
        ++compared;
    }
    assert_true(compared > 100);
}

static void test_invalid_input(void **state)
{
    (void)state;
    const double bad[3] = {NAN, INFINITY, -INFINITY};
    for (int k = 0; k < 6; ++k)
        for (int j = 0; j < 3; ++j) {
            double p[6] = {0, 0, 1, 0, 0, 0};
            p[k] = bad[j];
            tse_ik_result r;
            assert_int_equal(ik(p, &r), TSE_INVALID);
            assert_int_equal(r.scissor, 1);
        }
    /* A non-finite seed is malformed input too. */
    tse_real pose[6] = {0, 0, 1, 0, 0, 0}, seed[6] = {0.4, 0.4, 0.4, (tse_real)NAN, 0.4, 0.4};
    tse_ik_result r;
    assert_int_equal(tse_ik(&G, pose, seed, &r), TSE_INVALID);
}

static tse_status ik_with(const tse_params *pp, const double p[6], tse_ik_result *r)
{
    tse_geometry g;
    assert_int_equal(tse_geometry_init(&g, pp), TSE_PARAM_OK);
    tse_real pose[6];
    for (int k = 0; k < 6; ++k)
        pose[k] = (tse_real)p[k];
    return tse_ik(&g, pose, NULL, r);
}

static void test_each_status(void **state)
{
    (void)state;
    tse_ik_result r;
    const double far[6] = {0.8, 0, 1.0, 0, 0, 0};
    assert_int_equal(ik(far, &r), TSE_UNREACHABLE);
    /* Below the base: the mirror image of a valid pose solves the equations, but Z < 0. */
    const double below[6] = {0, 0, -0.5, 0, 0, 0};
    assert_int_equal(ik(below, &r), TSE_BELOW);
    assert_int_equal(r.scissor, 1);
    /* Above the extended stop (1.619 m) and below the retracted one (0.324 m) at the centre. */
    const double high[6] = {0, 0, 1.65, 0, 0, 0}, low[6] = {0, 0, 0.25, 0, 0, 0};
    assert_int_equal(ik(high, &r), TSE_ALPHA);
    assert_int_equal(ik(low, &r), TSE_ALPHA);
    /* Stroke: the home solution is 0.430 m; a 0.40 m stroke cannot hold it. */
    tse_params p = P;
    p.s_max = (tse_real)0.40;
    const double home[6] = {0, 0, 1.0, 0, 0, 0};
    assert_int_equal(ik_with(&p, home, &r), TSE_STROKE);
    assert_int_equal(r.scissor, 1);
    /* Order: at Z = 0.25 the slides are long (about 0.5 m) and the angle is out of its stop too:
     * alpha is checked first. */
    const double z25[6] = {0, 0, 0.25, 0, 0, 0};
    assert_int_equal(ik_with(&p, z25, &r), TSE_ALPHA);
    /* Singular: every margin is below a threshold of 0.999 (mu <= 1, about 0.997 at home). */
    p = P;
    p.mu_min = (tse_real)0.999;
    assert_int_equal(ik_with(&p, home, &r), TSE_SINGULAR);
    assert_int_equal(r.scissor, 1);
    /* Degenerate: the Hadamard ratio is well below 0.9 at home. */
    p = P;
    p.nu_min = (tse_real)0.9;
    assert_int_equal(ik_with(&p, home, &r), TSE_DEGENERATE);
    assert_true(r.scissor >= 1 && r.scissor <= 3);
    assert_true(r.nu < 0.9 && r.nu > 0);
}

/* The first failing scissor is named: moving far towards -X takes the plate away from scissor 1
 * (at +X), so 2 and 3 fail first; scissor 1's own slides must then be fine by hand. */
static void test_first_failing_scissor(void **state)
{
    (void)state;
    int seen = 0;
    for (double x = -0.2; x > -0.8 && !seen; x -= 0.005) {
        const double p[6] = {x, 0.05, 0.8, 0, 0, 0};
        tse_ik_result r;
        if (ik(p, &r) == TSE_OK || r.scissor == 1)
            continue;
        /* Scissor 1 passed every check on its own: positive slides inside the stroke and a
         * width inside the stops, from w^2 = s_A^2 + s_B^2 + 2 cos(2 eta) s_A s_B. */
        const double a = (double)r.q[0], b = (double)r.q[1];
        const double w = sqrt(a * a + b * b + 2 * cos(M_PI / 3) * a * b);
        const double l0 = 0.2647 * 1.727;
        assert_true(a > 0 && a <= 0.9 && b > 0 && b <= 0.9);
        assert_true(w <= 2 * l0 * cos(asin(0.324 / 1.727)) && w >= 2 * l0 * cos(asin(1.619 / 1.727)));
        seen = 1;
    }
    assert_true(seen);
}

static void test_invalid_params(void **state)
{
    (void)state;
    struct {
        int id;
        double value;
    } cases[] = {
        {TSE_PARAM_L, 0},         {TSE_PARAM_L, -1},         {TSE_PARAM_L, NAN},
        {TSE_PARAM_K1, 0},        {TSE_PARAM_K1, 1.01},      {TSE_PARAM_ETA, M_PI / 2},
        {TSE_PARAM_ETA, -M_PI / 2}, {TSE_PARAM_K3, -0.01},   {TSE_PARAM_K4, 0},
        {TSE_PARAM_ALPHA_MIN, 0}, {TSE_PARAM_ALPHA_MAX, 0.1}, {TSE_PARAM_ALPHA_MAX, M_PI / 2},
        {TSE_PARAM_S_MIN, -0.1},  {TSE_PARAM_S_MAX, 0.0},    {TSE_PARAM_MU_MIN, 1.0},
        {TSE_PARAM_NU_MIN, -1e-3}, {TSE_PARAM_K3, INFINITY}, {TSE_PARAM_NU_MIN, NAN},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        tse_params p = P;
        tse_real *f[TSE_PARAM_COUNT] = {NULL, &p.L, &p.k1, &p.eta, &p.k3, &p.k4, &p.alpha_min,
                                        &p.alpha_max, &p.s_min, &p.s_max, &p.mu_min, &p.nu_min};
        *f[cases[i].id] = (tse_real)cases[i].value;
        assert_int_equal(tse_params_check(&p), cases[i].id);
        tse_geometry g;
        assert_int_equal(tse_geometry_init(&g, &p), cases[i].id);
    }
    assert_int_equal(tse_params_check(&P), TSE_PARAM_OK);
    assert_string_equal(tse_param_name(TSE_PARAM_ALPHA_MAX), "alpha_max");
    for (int s = 0; s < TSE_STATUS_COUNT; ++s) {
        tse_status back;
        assert_int_equal(tse_status_parse(tse_status_name((tse_status)s), &back), 0);
        assert_int_equal(back, s);
    }
    tse_status back;
    assert_int_equal(tse_status_parse("bogus", &back), -1);
}

static void test_fk_of_ik(void **state)
{
    (void)state;
    srand(31);
    int n = 0;
    /* Bounded: a broken library must fail this test, not hang it. */
    for (int attempt = 0; attempt < 20000 && n < 500; ++attempt) {
        const double p[6] = {U(-0.3, 0.3), U(-0.3, 0.3), U(0.4, 1.5), U(-0.2, 0.2), U(-0.2, 0.2), U(-0.5, 0.5)};
        tse_ik_result r;
        if (ik(p, &r) != TSE_OK)
            continue;
        ++n;
        /* Seeded near the answer (the simulator seeds with the last pose). */
        tse_real seed[6];
        for (int k = 0; k < 6; ++k)
            seed[k] = (tse_real)(p[k] + U(-0.02, 0.02));
        tse_fk_result f;
        assert_int_equal(tse_fk(&G, r.q, seed, &f), TSE_OK);
        for (int k = 0; k < 6; ++k)
            assert_true(fabs((double)f.pose[k] - p[k]) <= POSE_TOL);
    }
    assert_int_equal(n, 500);
    /* Slides that belong to no pose: a failure, never a pose. */
    const tse_real q[6] = {0.05, 0.85, 0.85, 0.05, 0.05, 0.05};
    tse_fk_result f;
    assert_int_not_equal(tse_fk(&G, q, NULL, &f), TSE_OK);
    const tse_real qn[6] = {0.4, 0.4, (tse_real)NAN, 0.4, 0.4, 0.4};
    assert_int_equal(tse_fk(&G, qn, NULL, &f), TSE_INVALID);
}

static void test_jacobian_vs_differences(void **state)
{
    (void)state;
    srand(41);
#if defined(TSE_REAL_FLOAT) && TSE_REAL_FLOAT
    const double h = 1e-3, tol = 5e-3;
#else
    const double h = 1e-6, tol = 1e-7;
#endif
    int n = 0;
    for (int attempt = 0; attempt < 20000 && n < 200; ++attempt) {
        const double p[6] = {U(-0.3, 0.3), U(-0.3, 0.3), U(0.4, 1.5), U(-0.2, 0.2), U(-0.2, 0.2), U(-0.5, 0.5)};
        tse_ik_result r;
        if (ik(p, &r) != TSE_OK || r.mu[0] < 0.2 || r.mu[1] < 0.2 || r.mu[2] < 0.2)
            continue;
        tse_real pose[6], J[6][6];
        for (int k = 0; k < 6; ++k)
            pose[k] = (tse_real)p[k];
        assert_int_equal(tse_jacobian(&G, pose, r.q, J), TSE_OK);
        /* Central differences need both neighbours inside the workspace. */
        tse_ik_result a[6], b[6];
        int inside = 1;
        for (int c = 0; c < 6 && inside; ++c) {
            double pp[6], pm[6];
            for (int k = 0; k < 6; ++k)
                pp[k] = pm[k] = p[k];
            pp[c] += h;
            pm[c] -= h;
            inside = ik(pp, &a[c]) == TSE_OK && ik(pm, &b[c]) == TSE_OK;
        }
        if (!inside)
            continue;
        ++n;
        for (int c = 0; c < 6; ++c)
            for (int row = 0; row < 6; ++row) {
                const double fd = ((double)a[c].q[row] - (double)b[c].q[row]) / (2 * h);
                assert_true(fabs(fd - (double)J[row][c]) <= tol * (1 + fabs(fd)));
            }
    }
    assert_int_equal(n, 200);
}

/* U diag(s) V^T with U, V products of Givens rotations: the singular values are s. */
static void test_singular_values_and_hadamard(void **state)
{
    (void)state;
    srand(51);
    const double s[6] = {9.0, 5.0, 3.0, 1.0, 0.5, 0.1};
    double U_[6][6], V[6][6];
    for (int m = 0; m < 2; ++m) {
        double (*Q)[6] = m ? V : U_;
        for (int i = 0; i < 6; ++i)
            for (int j = 0; j < 6; ++j)
                Q[i][j] = i == j;
        for (int k = 0; k < 30; ++k) {
            const int a = rand() % 6, b = (a + 1 + rand() % 5) % 6;
            const double t = U(0, 2 * M_PI), c = cos(t), sn = sin(t);
            for (int i = 0; i < 6; ++i) {
                const double x = Q[i][a], y = Q[i][b];
                Q[i][a] = c * x - sn * y;
                Q[i][b] = sn * x + c * y;
            }
        }
    }
    tse_real A[6][6], sv[6];
    for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 6; ++j) {
            double x = 0;
            for (int k = 0; k < 6; ++k)
                x += U_[i][k] * s[k] * V[j][k];
            A[i][j] = (tse_real)x;
        }
    tse_singular_values(A, sv);
    for (int k = 0; k < 6; ++k)
        assert_true(fabs((double)sv[k] - s[k]) <= (sizeof(tse_real) == 4 ? 1e-3 : 1e-10) * s[0]);
    /* Orthogonal rows: ratio 1.  Two equal rows: 0. */
    tse_real O[6][6];
    for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 6; ++j)
            O[i][j] = (tse_real)(U_[i][j] * (i + 1));
    assert_true(fabs((double)tse_hadamard_ratio(O) - 1.0) < (sizeof(tse_real) == 4 ? 1e-5 : 1e-12));
    for (int j = 0; j < 6; ++j)
        O[5][j] = O[0][j];
    assert_true((double)tse_hadamard_ratio(O) < 1e-5);
}

/* sigma_z = 1/(sqrt(6)|ds/dZ|); from the vertical quadratic, ds/dZ = -Z / (A s - u0). */
static void test_sigma_z_and_haf(void **state)
{
    (void)state;
    const double L = 1.727, l0 = 0.2647 * L, d = (0.11765 - 0.0186) * L, eta = M_PI / 6;
    const double g = (1 - (L / l0) * (L / l0)) / 4, A = 1 - 2 * g * (1 + cos(2 * eta)), u0 = d * sin(eta);
    double lo = INFINITY, hi = 0;
    for (double z = 0.4; z < 1.6; z += 0.1) {
        tse_real sigma, haf;
        assert_int_equal(tse_sigma_z(&G, (tse_real)z, &sigma), TSE_OK);
        const double dsdz = -z / (A * vertical(z) - u0);
        assert_true(fabs((double)sigma - 1 / (sqrt(6) * fabs(dsdz))) <= 1e-6 * (double)sigma);
        assert_int_equal(tse_haf(&P, (tse_real)z, &haf), TSE_OK);
        /* The rigid design (g = 0, A = 1) over the scissor design, both from the quadratic. */
        const double s_r = u0 + sqrt(u0 * u0 - (d * d + z * z - L * L));
        const double expect = (A * vertical(z) - u0) / (s_r - u0);
        assert_true(fabs((double)haf - expect) <= 1e-5 * expect);
        lo = (double)haf < lo ? (double)haf : lo;
        hi = (double)haf > hi ? (double)haf : hi;
    }
    /* Amplification, and nearly independent of Z as the paper says. */
    assert_true(lo > 1.0);
    assert_true((hi - lo) / lo < 0.02);
    print_message("HAF over Z: %.4f .. %.4f (the paper gives 11.487)\n", lo, hi);
}

static void test_workspace(void **state)
{
    (void)state;
    const tse_real zero[3] = {0, 0, 0};
    long reach, total;
    assert_int_equal(tse_workspace(&G, 21, 36, 41, zero, &reach, &total), TSE_OK);
    assert_int_equal(total, 21 * 36 * 41);
    const double frac = (double)reach / (double)total;
    print_message("workspace fraction %.4f on 21 x 36 x 41 (the paper gives 0.28)\n", frac);
    assert_true(frac > 0.22 && frac < 0.34);
    /* The vertical axis inside the stops is all reachable: 1 x 36 points at each such height. */
    long r1, t1;
    assert_int_equal(tse_workspace(&G, 2, 1, 2, zero, &r1, &t1), TSE_OK);
    assert_int_equal(t1, 4); /* Z = 0 and Z = L: outside */
    assert_int_equal(r1, 0);
    const tse_real nan3[3] = {0, (tse_real)NAN, 0};
    assert_int_equal(tse_workspace(&G, 1, 36, 41, zero, &r1, &t1), TSE_INVALID);
    assert_int_equal(tse_workspace(&G, 21, 0, 41, zero, &r1, &t1), TSE_INVALID);
    assert_int_equal(tse_workspace(&G, 21, 36, 1, zero, &r1, &t1), TSE_INVALID);
    assert_int_equal(tse_workspace(&G, 21, 36, 41, nan3, &r1, &t1), TSE_INVALID);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_defaults),
        cmocka_unit_test(test_worked_values),
        cmocka_unit_test(test_vertical_closed_form),
        cmocka_unit_test(test_symmetry),
        cmocka_unit_test(test_invalid_input),
        cmocka_unit_test(test_each_status),
        cmocka_unit_test(test_first_failing_scissor),
        cmocka_unit_test(test_invalid_params),
        cmocka_unit_test(test_fk_of_ik),
        cmocka_unit_test(test_jacobian_vs_differences),
        cmocka_unit_test(test_singular_values_and_hadamard),
        cmocka_unit_test(test_sigma_z_and_haf),
        cmocka_unit_test(test_workspace),
    };
    return cmocka_run_group_tests(tests, setup, NULL);
}
