/* Design metrics (kinematics.md, "Forward kinematics, Jacobian, metrics"): sigma_z and HAF in
 * closed form on the vertical axis, the workspace percentage against a count by the reference. */
#include "test_common.h"

/* On the vertical axis F2(s, Z) = D s^2 - 2 u0 s + (r^2 + Z^2 - L^2) = 0 (r = r_top - r_act,
 * u0 = r sin(eta), D = 1 - 2 g (1 + c)).  Differentiating: (2 D s - 2 u0) ds + 2 Z dZ = 0, so
 * ds/dZ = -Z / (D s - u0), and on the branch D s - u0 = sqrt(u0^2 - D (r^2 + Z^2 - L^2)) > 0:
 * sigma_z = 1 / (sqrt(6) |ds/dZ|) = sqrt(u0^2 + D (L^2 - r^2 - Z^2)) / (sqrt(6) Z).
 * For k1 = 1, g = 0 and D = 1; so HAF(Z) = sqrt(u0^2 + D K) / sqrt(u0^2 + K), K = L^2 - r^2 - Z^2,
 * which tends to sqrt(D) where u0^2 << K: nearly independent of Z. */
typedef struct {
    double L, r, u0, D;
} vertical_consts;

static vertical_consts vconsts(const tse_params *p)
{
    vertical_consts v;
    double l0 = p->k1 * p->L;
    double gg = (1.0 - ((double)p->L / l0) * ((double)p->L / l0)) / 4.0;
    v.L = p->L;
    v.r = ((double)p->k4 - (double)p->k3) * p->L;
    v.u0 = v.r * sin((double)p->eta);
    v.D = 1.0 - 2.0 * gg * (1.0 + cos(2.0 * p->eta));
    return v;
}

static double sigma_closed(const vertical_consts *v, double z)
{
    double K = v->L * v->L - v->r * v->r - z * z;
    return sqrt(v->u0 * v->u0 + v->D * K) / (sqrt(6.0) * z);
}

static double haf_closed(const vertical_consts *v, double z)
{
    double K = v->L * v->L - v->r * v->r - z * z;
    return sqrt(v->u0 * v->u0 + v->D * K) / sqrt(v->u0 * v->u0 + K);
}

/* Height of the vertical pose at slide s (from F2), for the heights inside the alpha stops. */
static double z_of_s(const vertical_consts *v, double s)
{
    return sqrt(v->L * v->L - v->r * v->r + 2 * v->u0 * s - v->D * s * s);
}

static void stops_heights(const tse_params *p, double *z_lo, double *z_hi)
{
    vertical_consts v = vconsts(p);
    double l0 = p->k1 * p->L, k = sqrt(2.0 * (1.0 + cos(2.0 * p->eta)));
    *z_lo = z_of_s(&v, 2 * l0 * cos((double)p->alpha_min) / k);
    *z_hi = z_of_s(&v, 2 * l0 * cos((double)p->alpha_max) / k);
}

static void test_sigma_z_closed_form(void **state)
{
    (void)state;
    tse_params p;
    tse_params_default(&p);
    tse_geometry g;
    assert_int_equal(tse_geometry_init(&g, &p), TSE_PARAM_OK);
    vertical_consts v = vconsts(&p);
    /* also a finite-difference check of the closed form itself through the reference */
    tse_params pd;
    tse_params_default(&pd);
    orc_params op = test_orc_params(&pd);
    orc_geom og;
    orc_geom_init(&og, &op);
    for (int n = 0; n <= 24; n++) {
        double z = 0.3 + 1.35 * n / 24.0;
        tse_real sigma = -1;
        EXPECT_STATUS(tse_sigma_z(&g, (tse_real)z, &sigma), TSE_OK);
        double want = sigma_closed(&v, (double)(tse_real)z);
        EXPECT_NEAR(sigma, want, (IS_FLOAT ? 1e-4 : 1e-9) * want);
        orc_real h = 1e-7L;
        orc_real ds = (orc_vertical_slide(&og, (orc_real)(tse_real)z + h) -
                       orc_vertical_slide(&og, (orc_real)(tse_real)z - h)) /
                      (2 * h);
        EXPECT_NEAR(1.0 / (sqrt(6.0) * fabs((double)ds)), want, 1e-6 * want);
    }
    /* beyond the branch */
    tse_real sigma;
    EXPECT_STATUS(tse_sigma_z(&g, (tse_real)2.0, &sigma), TSE_UNREACHABLE);
    EXPECT_STATUS(tse_sigma_z(&g, (tse_real)1.715, &sigma), TSE_UNREACHABLE);
}

static void test_haf(void **state)
{
    (void)state;
    tse_params p;
    tse_params_default(&p);
    vertical_consts v = vconsts(&p);
    double z_lo, z_hi;
    stops_heights(&p, &z_lo, &z_hi);
    double lo = 1e9, hi = 0, mid = 0;
    for (int n = 0; n <= 20; n++) {
        double z = z_lo + (z_hi - z_lo) * n / 20.0;
        tse_real haf = -1;
        EXPECT_STATUS(tse_haf(&p, (tse_real)z, &haf), TSE_OK);
        double want = haf_closed(&v, (double)(tse_real)z);
        EXPECT_NEAR(haf, want, (IS_FLOAT ? 1e-4 : 1e-9) * want);
        if (haf < lo)
            lo = haf;
        if (haf > hi)
            hi = haf;
        if (n == 10)
            mid = haf;
    }
    print_message("HAF of the prototype over Z in [%.3f, %.3f]: %.4f .. %.4f (%.4f at mid "
                  "height; sqrt(D) = %.4f, D = %.4f); the paper states 11.487\n",
                  z_lo, z_hi, lo, hi, mid, sqrt(v.D), v.D);
    /* the physics: the short lowest link amplifies height, and nearly uniformly in Z */
    assert_true(lo > 1.0);
    assert_true((hi - lo) / mid < 0.05);
    /* with k1 = 1 the design is compared with itself */
    tse_params p1 = p;
    p1.k1 = 1;
    tse_real haf;
    EXPECT_STATUS(tse_haf(&p1, (tse_real)1.0, &haf), TSE_OK);
    EXPECT_NEAR(haf, 1.0, IS_FLOAT ? 1e-5 : 1e-12);
    /* an invalid design is rejected */
    tse_params bad = p;
    bad.L = -1;
    tse_status st = tse_haf(&bad, (tse_real)1.0, &haf);
    assert_true(st != TSE_OK);
    /* beyond the branch */
    EXPECT_STATUS(tse_haf(&p, (tse_real)2.0, &haf), TSE_UNREACHABLE);
}

/* Count the grid with the reference; points too close to a threshold to call are counted apart. */
static void reference_workspace(const orc_geom *og, int n_r, int n_phi, int n_z,
                                const double orient[3], long *sure, long *unsure, long *axis_ok,
                                long *axis_in_stops)
{
    orc_tol tol = test_orc_tol();
    const orc_real PI_L = 3.141592653589793238462643383279502884L;
    *sure = *unsure = *axis_ok = *axis_in_stops = 0;
    for (int i = 0; i < n_r; i++)
        for (int j = 0; j < n_phi; j++)
            for (int k = 0; k < n_z; k++) {
                /* the grid in the test's precision, as the library would form it */
                tse_real r = (tse_real)(og->p.L / 2 * i / (n_r - 1));
                tse_real phi = (tse_real)(2 * PI_L * j / n_phi);
                tse_real z = (tse_real)(og->p.L * k / (n_z - 1));
                orc_real pose[6] = {(orc_real)r * cosl((orc_real)phi),
                                    (orc_real)r * sinl((orc_real)phi),
                                    (orc_real)z,
                                    (orc_real)orient[0],
                                    (orc_real)orient[1],
                                    (orc_real)orient[2]};
                orc_result o;
                orc_ik(og, pose, NULL, &tol, &o);
                if (o.ambiguous)
                    (*unsure)++;
                else if (o.status == TSE_OK)
                    (*sure)++;
                if (i == 0 && o.status == TSE_OK && !o.ambiguous)
                    (*axis_ok)++;
                if (i == 0 && orient[0] == 0 && orient[1] == 0) {
                    orc_real s = orc_vertical_slide(og, (orc_real)z);
                    orc_real w = s * sqrtl(2 * (1 + og->c));
                    if (isfinite(s) && w <= 2 * og->l0 * cosl(og->p.alpha_min) &&
                        w >= 2 * og->l0 * cosl(og->p.alpha_max))
                        (*axis_in_stops)++;
                }
            }
}

static void test_workspace_prototype(void **state)
{
    (void)state;
    tse_params p;
    tse_params_default(&p);
    tse_geometry g;
    orc_geom og;
    test_geometries(&p, &g, &og);
    const tse_real zero[3] = {0, 0, 0};
    long reach = -1, total = -1;
    EXPECT_STATUS(tse_workspace(&g, 21, 36, 41, zero, &reach, &total), TSE_OK);
    assert_int_equal(total, 21L * 36 * 41);
    double frac = (double)reach / (double)total;
    print_message("workspace of the prototype, grid 21 x 36 x 41, zero orientation: %ld of %ld "
                  "= %.4f (the paper: 0.28)\n",
                  reach, total, frac);
    assert_true(frac > 0.20 && frac < 0.36);
    /* the same count by the reference */
    long sure, unsure, axis_ok, axis_in_stops;
    const double o0[3] = {0, 0, 0};
    reference_workspace(&og, 21, 36, 41, o0, &sure, &unsure, &axis_ok, &axis_in_stops);
    print_message("reference: %ld reachable, %ld too close to call; on the axis %ld of %ld "
                  "heights inside the stops accepted (x 36 directions)\n",
                  sure, unsure, axis_ok / 36, axis_in_stops / 36);
    if (!(reach >= sure && reach <= sure + unsure)) {
        print_error("workspace count %ld outside the reference's [%ld, %ld]\n", reach, sure,
                    sure + unsure);
        fail();
    }
    /* every axis height inside the stops is reachable (stroke, margins hold there) */
    assert_int_equal(axis_ok, axis_in_stops);
    assert_true(axis_in_stops >= 30 * 36);
    /* the axis alone: r_1 = L/2 is beyond reach, so a 2-radius, 1-direction grid counts the axis */
    EXPECT_STATUS(tse_workspace(&g, 2, 1, 41, zero, &reach, &total), TSE_OK);
    assert_int_equal(total, 2 * 41);
    reference_workspace(&og, 2, 1, 41, o0, &sure, &unsure, &axis_ok, &axis_in_stops);
    assert_int_equal(unsure, 0);
    assert_int_equal(sure, axis_in_stops);
    assert_int_equal(reach, axis_in_stops);
}

static void test_workspace_tilted(void **state)
{
    (void)state;
    tse_params p;
    tse_params_default(&p);
    tse_geometry g;
    orc_geom og;
    test_geometries(&p, &g, &og);
    const double orients[2][3] = {{0.1, 0.0, 0.0}, {0.05, -0.15, 0.4}};
    for (int n = 0; n < 2; n++) {
        tse_real o[3] = {(tse_real)orients[n][0], (tse_real)orients[n][1],
                         (tse_real)orients[n][2]};
        long reach, total;
        EXPECT_STATUS(tse_workspace(&g, 11, 12, 21, o, &reach, &total), TSE_OK);
        assert_int_equal(total, 11L * 12 * 21);
        double od[3] = {(double)o[0], (double)o[1], (double)o[2]};
        long sure, unsure, axis_ok, axis_in_stops;
        reference_workspace(&og, 11, 12, 21, od, &sure, &unsure, &axis_ok, &axis_in_stops);
        print_message("workspace at orientation (%g, %g, %g): %ld of %ld (reference %ld, %ld too "
                      "close to call)\n",
                      od[0], od[1], od[2], reach, total, sure, unsure);
        if (!(reach >= sure && reach <= sure + unsure)) {
            print_error("workspace count %ld outside the reference's [%ld, %ld]\n", reach, sure,
                        sure + unsure);
            fail();
        }
    }
}

static void test_workspace_invalid(void **state)
{
    (void)state;
    tse_params p;
    tse_params_default(&p);
    tse_geometry g;
    assert_int_equal(tse_geometry_init(&g, &p), TSE_PARAM_OK);
    const tse_real zero[3] = {0, 0, 0};
    long reach, total;
    const int grids[][3] = {{1, 36, 41}, {0, 36, 41}, {-3, 36, 41}, {21, 0, 41},
                            {21, -1, 41}, {21, 36, 1}, {21, 36, 0}, {21, 36, -5}};
    for (size_t n = 0; n < sizeof grids / sizeof grids[0]; n++)
        EXPECT_STATUS(tse_workspace(&g, grids[n][0], grids[n][1], grids[n][2], zero, &reach,
                                    &total),
                      TSE_INVALID);
    const double bad[3] = {NAN, INFINITY, -INFINITY};
    for (int k = 0; k < 3; k++)
        for (int b = 0; b < 3; b++) {
            tse_real o[3] = {0, 0, 0};
            o[k] = (tse_real)bad[b];
            EXPECT_STATUS(tse_workspace(&g, 3, 4, 5, o, &reach, &total), TSE_INVALID);
        }
    /* the smallest valid grid */
    EXPECT_STATUS(tse_workspace(&g, 2, 1, 2, zero, &reach, &total), TSE_OK);
    assert_int_equal(total, 4);
    /* sigma_z with a non-finite height */
    tse_real sigma;
    EXPECT_STATUS(tse_sigma_z(&g, (tse_real)NAN, &sigma), TSE_INVALID);
    tse_real haf;
    EXPECT_STATUS(tse_haf(&p, (tse_real)INFINITY, &haf), TSE_INVALID);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sigma_z_closed_form),
        cmocka_unit_test(test_haf),
        cmocka_unit_test(test_workspace_invalid),
        cmocka_unit_test(test_workspace_prototype),
        cmocka_unit_test(test_workspace_tilted),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
