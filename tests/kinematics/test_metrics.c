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

/* ------------------------------------------------------------------ the design study's figures */

/* Designs around the prototype that the study sweeps through, and corners of the parameter space:
 * eta = 0 puts both slides of a scissor on one line (the strokes' midpoints then fill a segment, not
 * a parallelogram), a positive s_min and narrow stops move the band that tse_workspace_count screens
 * with. */
typedef struct {
    const char *name;
    double k1, eta_deg, k3, k4, s_min, s_max, alpha_min_deg, alpha_max_deg; /* NAN: the prototype's */
} study_design;

static const study_design study_designs[] = {
    {"prototype", NAN, NAN, NAN, NAN, NAN, NAN, NAN, NAN},
    {"k1 = 0.1", 0.1, NAN, NAN, NAN, NAN, NAN, NAN, NAN},
    {"k1 = 0.5", 0.5, NAN, NAN, NAN, NAN, NAN, NAN, NAN},
    {"k1 = 1", 1.0, NAN, NAN, NAN, NAN, NAN, NAN, NAN},
    {"eta = -30 deg", NAN, -30, NAN, NAN, NAN, NAN, NAN, NAN},
    {"eta = 0", NAN, 0, NAN, NAN, NAN, NAN, NAN, NAN},
    {"eta = 60 deg", NAN, 60, NAN, NAN, NAN, NAN, NAN, NAN},
    {"eta = -85 deg", NAN, -85, NAN, NAN, NAN, NAN, NAN, NAN},
    {"k3 = 0.15", NAN, NAN, 0.15, NAN, NAN, NAN, NAN, NAN},
    {"k4 = 0.03", NAN, NAN, NAN, 0.03, NAN, NAN, NAN, NAN},
    {"stroke 0.2 .. 0.5 m", NAN, NAN, NAN, NAN, 0.2, 0.5, NAN, NAN},
    {"stops 30 .. 50 deg", NAN, NAN, NAN, NAN, NAN, NAN, 30, 50},
};
enum { N_STUDY_DESIGNS = (int)(sizeof study_designs / sizeof study_designs[0]) };

static tse_params study_params(const study_design *d)
{
    tse_params p;
    tse_params_default(&p);
    const double deg = 3.14159265358979323846 / 180.0;
    if (!isnan(d->k1))
        p.k1 = (tse_real)d->k1;
    if (!isnan(d->eta_deg))
        p.eta = (tse_real)(d->eta_deg * deg);
    if (!isnan(d->k3))
        p.k3 = (tse_real)d->k3;
    if (!isnan(d->k4))
        p.k4 = (tse_real)d->k4;
    if (!isnan(d->s_min))
        p.s_min = (tse_real)d->s_min;
    if (!isnan(d->s_max))
        p.s_max = (tse_real)d->s_max;
    if (!isnan(d->alpha_min_deg))
        p.alpha_min = (tse_real)(d->alpha_min_deg * deg);
    if (!isnan(d->alpha_max_deg))
        p.alpha_max = (tse_real)(d->alpha_max_deg * deg);
    return p;
}

/* The grid points are the paper's (kinematics.md), and solving each one counts what tse_workspace
 * counts; tse_workspace_count's screen never loses a point tse_ik would accept. */
static void test_workspace_points_and_count(void **state)
{
    (void)state;
    const double orients[2][3] = {{0, 0, 0}, {0, 0.3490658503988659, 0}}; /* level; pitch 20 deg */
    const int nr = 9, nphi = 12, nz = 17;
    for (int d = 0; d < N_STUDY_DESIGNS; d++) {
        tse_params p = study_params(&study_designs[d]);
        tse_geometry g;
        assert_int_equal(tse_geometry_init(&g, &p), TSE_PARAM_OK);
        for (int o = 0; o < 2; o++) {
            const tse_real orient[3] = {(tse_real)orients[o][0], (tse_real)orients[o][1], (tse_real)orients[o][2]};
            long by_points = 0, n = 0;
            for (int k = 0; k < nz; k++)
                for (int i = 0; i < nr; i++)
                    for (int j = 0; j < nphi; j++) {
                        tse_real pose[6];
                        EXPECT_STATUS(tse_workspace_pose(&g, nr, nphi, nz, i, j, k, orient, pose), TSE_OK);
                        const double L = (double)p.L, r = L / 2 * i / (nr - 1);
                        const double phi = 2 * 3.14159265358979323846 * j / nphi, z = L * k / (nz - 1);
                        const double tol = (IS_FLOAT ? 1e-6 : 1e-14) * L;
                        EXPECT_NEAR(pose[0], r * cos(phi), tol);
                        EXPECT_NEAR(pose[1], r * sin(phi), tol);
                        EXPECT_NEAR(pose[2], z, tol);
                        for (int c = 0; c < 3; c++)
                            assert_true(pose[3 + c] == orient[c]);
                        tse_ik_result res;
                        by_points += tse_ik(&g, pose, NULL, &res) == TSE_OK;
                        ++n;
                    }
            long plain, total, screened, total2;
            EXPECT_STATUS(tse_workspace(&g, nr, nphi, nz, orient, &plain, &total), TSE_OK);
            EXPECT_STATUS(tse_workspace_count(&g, nr, nphi, nz, orient, &screened, &total2), TSE_OK);
            if (by_points != plain || screened != plain || total != n || total2 != n) {
                print_error("%s, orientation %d: points %ld, tse_workspace %ld, tse_workspace_count %ld "
                            "(totals %ld, %ld, %ld)\n",
                            study_designs[d].name, o, by_points, plain, screened, n, total, total2);
                fail();
            }
        }
    }
    /* the paper's grid for the prototype, level: the sweep's own figure */
    tse_params p;
    tse_params_default(&p);
    tse_geometry g;
    assert_int_equal(tse_geometry_init(&g, &p), TSE_PARAM_OK);
    const tse_real zero[3] = {0, 0, 0};
    long plain, screened, total;
    EXPECT_STATUS(tse_workspace(&g, 16, 24, 32, zero, &plain, &total), TSE_OK);
    EXPECT_STATUS(tse_workspace_count(&g, 16, 24, 32, zero, &screened, &total), TSE_OK);
    assert_int_equal(screened, plain);
    print_message("workspace of the prototype on the paper's 16 x 24 x 32 grid: %ld of %ld = %.4f\n", plain, total,
                  (double)plain / (double)total);
}

static void test_workspace_pose_invalid(void **state)
{
    (void)state;
    tse_params p;
    tse_params_default(&p);
    tse_geometry g;
    assert_int_equal(tse_geometry_init(&g, &p), TSE_PARAM_OK);
    const tse_real zero[3] = {0, 0, 0}, bad[3] = {0, (tse_real)NAN, 0};
    const int cases[][6] = {{1, 4, 5, 0, 0, 0},  {3, 0, 5, 0, 0, 0},  {3, 4, 1, 0, 0, 0},
                            {3, 4, 5, -1, 0, 0}, {3, 4, 5, 3, 0, 0},  {3, 4, 5, 0, -1, 0},
                            {3, 4, 5, 0, 4, 0},  {3, 4, 5, 0, 0, -1}, {3, 4, 5, 0, 0, 5}};
    for (size_t n = 0; n < sizeof cases / sizeof cases[0]; n++) {
        const int *c = cases[n];
        tse_real pose[6] = {0, 0, 0, 0, 0, 0};
        EXPECT_STATUS(tse_workspace_pose(&g, c[0], c[1], c[2], c[3], c[4], c[5], zero, pose), TSE_INVALID);
        for (int k = 0; k < 6; k++)
            assert_true(isnan(pose[k]));
    }
    tse_real pose[6];
    EXPECT_STATUS(tse_workspace_pose(&g, 3, 4, 5, 2, 3, 4, bad, pose), TSE_INVALID);
    EXPECT_STATUS(tse_workspace_pose(&g, 3, 4, 5, 2, 3, 4, zero, pose), TSE_OK);
    long reach = -1, total = -1;
    EXPECT_STATUS(tse_workspace_count(&g, 1, 4, 5, zero, &reach, &total), TSE_INVALID);
    assert_true(reach == 0 && total == 0);
    EXPECT_STATUS(tse_workspace_count(&g, 3, 0, 5, zero, &reach, &total), TSE_INVALID);
    EXPECT_STATUS(tse_workspace_count(&g, 3, 4, 1, zero, &reach, &total), TSE_INVALID);
    EXPECT_STATUS(tse_workspace_count(&g, 3, 4, 5, bad, &reach, &total), TSE_INVALID);
}

/* The cells of the grid's points (tse_workspace_cell_volume) fill the cylinder r <= L/2,
 * 0 <= Z <= L exactly, pi L^3 / 4, and a cell is what the hand algebra gives: on a 3-ring grid
 * (dr = L/4) the rings are r = 0 .. L/8, L/8 .. 3L/8, 3L/8 .. L/2; on 5 layers (dZ = L/4) the
 * floor and top cells are L/8 high, the others L/4. */
static void test_workspace_cells_fill_cylinder(void **state)
{
    (void)state;
    tse_params p;
    tse_params_default(&p);
    p.L = (tse_real)1.3;
    tse_geometry g;
    assert_int_equal(tse_geometry_init(&g, &p), TSE_PARAM_OK);
    const double L = (double)p.L, pi = 3.14159265358979323846, tol = IS_FLOAT ? 1e-5 : 1e-13;
    const int grids[][3] = {{2, 1, 2}, {3, 4, 5}, {16, 24, 32}, {21, 36, 41}, {7, 1, 3}};
    for (size_t n = 0; n < sizeof grids / sizeof grids[0]; n++) {
        const int *gr = grids[n];
        double sum = 0;
        for (int k = 0; k < gr[2]; k++)
            for (int i = 0; i < gr[0]; i++) {
                tse_real cell;
                EXPECT_STATUS(tse_workspace_cell_volume(&g, gr[0], gr[1], gr[2], i, k, &cell), TSE_OK);
                assert_true(cell > 0);
                sum += (double)cell * gr[1];
            }
        EXPECT_NEAR(sum, pi * L * L * L / 4, tol * L * L * L);
    }
    const double ring[3][2] = {{0, L / 8}, {L / 8, 3 * L / 8}, {3 * L / 8, L / 2}};
    const double layer[5] = {L / 8, L / 4, L / 4, L / 4, L / 8};
    for (int i = 0; i < 3; i++)
        for (int k = 0; k < 5; k++) {
            tse_real cell;
            EXPECT_STATUS(tse_workspace_cell_volume(&g, 3, 4, 5, i, k, &cell), TSE_OK);
            const double want = pi / 4 * (ring[i][1] * ring[i][1] - ring[i][0] * ring[i][0]) * layer[k];
            EXPECT_NEAR(cell, want, tol * want);
        }
    const int bad[][5] = {{1, 4, 5, 0, 0}, {3, 0, 5, 0, 0}, {3, 4, 1, 0, 0}, {3, 4, 5, -1, 0},
                          {3, 4, 5, 3, 0}, {3, 4, 5, 0, -1}, {3, 4, 5, 0, 5}};
    for (size_t n = 0; n < sizeof bad / sizeof bad[0]; n++) {
        tse_real cell = 1;
        EXPECT_STATUS(tse_workspace_cell_volume(&g, bad[n][0], bad[n][1], bad[n][2], bad[n][3], bad[n][4], &cell),
                      TSE_INVALID);
        assert_true(isnan(cell));
    }
}

/* The reachable volume: the cells of the points tse_ik reaches, counted one by one here, and its
 * count tse_workspace's.  A design scaled as a whole by 2 (L and the stroke; k1..k4, the stops and
 * the margins are ratios and angles) reaches the same points, every length doubled exactly in
 * binary, so its volume is 8 times as large while the fraction stays: the figure that tells designs
 * of different size apart. */
static void test_workspace_volume(void **state)
{
    (void)state;
    const tse_real zero[3] = {0, 0, 0}, bad[3] = {0, (tse_real)NAN, 0};
    const int nr = 9, nphi = 12, nz = 17;
    for (int d = 0; d < N_STUDY_DESIGNS; d++) {
        tse_params p = study_params(&study_designs[d]);
        tse_geometry g;
        assert_int_equal(tse_geometry_init(&g, &p), TSE_PARAM_OK);
        double by_points = 0;
        for (int k = 0; k < nz; k++)
            for (int i = 0; i < nr; i++)
                for (int j = 0; j < nphi; j++) {
                    tse_real pose[6], cell;
                    tse_ik_result res;
                    (void)tse_workspace_pose(&g, nr, nphi, nz, i, j, k, zero, pose);
                    EXPECT_STATUS(tse_workspace_cell_volume(&g, nr, nphi, nz, i, k, &cell), TSE_OK);
                    if (tse_ik(&g, pose, NULL, &res) == TSE_OK)
                        by_points += (double)cell;
                }
        long reach, total, plain, total2;
        tse_real volume;
        EXPECT_STATUS(tse_workspace_volume(&g, nr, nphi, nz, zero, &reach, &total, &volume), TSE_OK);
        EXPECT_STATUS(tse_workspace(&g, nr, nphi, nz, zero, &plain, &total2), TSE_OK);
        assert_int_equal(reach, plain);
        assert_int_equal(total, total2);
        EXPECT_NEAR(volume, by_points, (IS_FLOAT ? 1e-5 : 1e-13) * (double)p.L * p.L * p.L);

        tse_params big = p;
        big.L *= 2;
        big.s_min *= 2;
        big.s_max *= 2;
        tse_geometry gb;
        assert_int_equal(tse_geometry_init(&gb, &big), TSE_PARAM_OK);
        long reach_b, total_b;
        tse_real volume_b;
        EXPECT_STATUS(tse_workspace_volume(&gb, nr, nphi, nz, zero, &reach_b, &total_b, &volume_b), TSE_OK);
        if (reach_b != reach || fabs((double)volume_b - 8 * (double)volume) > (IS_FLOAT ? 1e-5 : 1e-12) * volume_b) {
            print_error("%s scaled by 2: %ld points, %.9g m^3 against %ld, 8 x %.9g m^3\n", study_designs[d].name,
                        reach_b, (double)volume_b, reach, (double)volume);
            fail();
        }
    }
    long reach = -1, total = -1;
    tse_real volume = 0;
    tse_params p;
    tse_params_default(&p);
    tse_geometry g;
    assert_int_equal(tse_geometry_init(&g, &p), TSE_PARAM_OK);
    EXPECT_STATUS(tse_workspace_volume(&g, 1, 4, 5, zero, &reach, &total, &volume), TSE_INVALID);
    assert_true(reach == 0 && total == 0 && isnan(volume));
    EXPECT_STATUS(tse_workspace_volume(&g, 3, 4, 5, bad, &reach, &total, &volume), TSE_INVALID);
    assert_true(isnan(volume));
}

/* The workspace of designs the study compares, counted by the long-double reference. */
static void test_workspace_designs_oracle(void **state)
{
    (void)state;
    const int designs[] = {2, 4, 6, 8};
    for (size_t n = 0; n < sizeof designs / sizeof designs[0]; n++) {
        const study_design *d = &study_designs[designs[n]];
        tse_params p = study_params(d);
        tse_geometry g;
        orc_geom og;
        test_geometries(&p, &g, &og);
        const tse_real zero[3] = {0, 0, 0};
        const double o0[3] = {0, 0, 0};
        long reach, total, sure, unsure, axis_ok, axis_in_stops;
        EXPECT_STATUS(tse_workspace_count(&g, 11, 12, 21, zero, &reach, &total), TSE_OK);
        reference_workspace(&og, 11, 12, 21, o0, &sure, &unsure, &axis_ok, &axis_in_stops);
        print_message("workspace, %s: %ld of %ld (reference %ld, %ld too close to call)\n", d->name, reach, total,
                      sure, unsure);
        if (!(reach >= sure && reach <= sure + unsure)) {
            print_error("%s: count %ld outside the reference's [%ld, %ld]\n", d->name, reach, sure, sure + unsure);
            fail();
        }
    }
}

/* On the vertical axis (closed form of the header comment) M has rows 2 (s - u0) (1, -1) and
 * (2 (s - u0) - 2 G, -2 G) with G = g s (1 + c), and det M = 4 (s - u0) (D s - u0). */
static double mu_closed(const vertical_consts *v, double gg, double c, double s)
{
    const double G = gg * s * (1 + c);
    const double det = 4 * (s - v->u0) * (v->D * s - v->u0);
    const double n1 = 2 * sqrt(2.0) * fabs(s - v->u0);
    const double n2 = 2 * sqrt((s - v->u0 - G) * (s - v->u0 - G) + G * G);
    return det / (n1 * n2);
}

/* dq/dp of the reference at (pose, q): -M_i^-1 dF_i/dp per scissor, rotation columns back in
 * metres per radian (the reference divides them by r_top for nu). */
static void oracle_dq_dp(const orc_geom *og, const orc_real pose[6], const orc_real q[6], orc_real J[6][6])
{
    orc_real Fp[6][6], C[3][3];
    orc_constraint_jacobian(og, pose, q, Fp);
    orc_joints(og, pose, C);
    for (int i = 0; i < 3; i++) {
        orc_real F[2], M[2][2];
        orc_residual(og, i, C[i], q[2 * i], q[2 * i + 1], F, M);
        const orc_real det = M[0][0] * M[1][1] - M[0][1] * M[1][0];
        for (int col = 0; col < 6; col++) {
            const orc_real scale = col < 3 ? 1.0L : og->r_top;
            const orc_real f1 = Fp[2 * i][col] * scale, f2 = Fp[2 * i + 1][col] * scale;
            J[2 * i][col] = -(M[1][1] * f1 - M[0][1] * f2) / det;
            J[2 * i + 1][col] = -(M[0][0] * f2 - M[1][0] * f1) / det;
        }
    }
}

/* The profile against the closed forms of the axis (sigma_z, mu) and the reference's Jacobian:
 * the singular values s_k of dp/dq are those of J = dq/dp inverted, so sum 1/s_k^2 = |J|_F^2,
 * sum 1/s_k^4 = |J^T J|_F^2 and prod 1/s_k = |det J| (the Hadamard ratio times the row norms);
 * three invariants that pin down six values that also come in the x-y pairs of the symmetry. */
static void test_vertical_profile(void **state)
{
    (void)state;
    const int designs[] = {0, 2, 4, 6, 8, 9};
    const double rel = IS_FLOAT ? 2e-4 : 1e-9;
    for (size_t n = 0; n < sizeof designs / sizeof designs[0]; n++) {
        const study_design *d = &study_designs[designs[n]];
        tse_params p = study_params(d);
        tse_geometry g;
        orc_geom og;
        test_geometries(&p, &g, &og);
        vertical_consts v = vconsts(&p);
        const double l0 = (double)p.k1 * (double)p.L, gg = (1.0 - ((double)p.L / l0) * ((double)p.L / l0)) / 4.0;
        const double c = cos(2.0 * (double)p.eta);
        const double z_lo = (double)p.L * sin((double)p.alpha_min), z_hi = (double)p.L * sin((double)p.alpha_max);
        for (int k = 0; k <= 8; k++) {
            const tse_real z = (tse_real)(z_lo + (z_hi - z_lo) * k / 8.0);
            tse_vertical_figures f;
            EXPECT_STATUS(tse_vertical_profile(&g, z, &f), TSE_OK);
            const orc_real s = orc_vertical_slide(&og, (orc_real)z);
            EXPECT_NEAR(f.s, (double)s, IS_FLOAT ? 2e-6 : 1e-9);
            const double sig = sigma_closed(&v, (double)z);
            EXPECT_NEAR(f.sigma_z, sig, rel * sig);
            tse_real sig_lib;
            EXPECT_STATUS(tse_sigma_z(&g, z, &sig_lib), TSE_OK);
            EXPECT_NEAR(f.sigma_z, sig_lib, rel * sig);
            EXPECT_NEAR(f.mu_min, mu_closed(&v, gg, c, (double)s), IS_FLOAT ? 1e-4 : 1e-9);

            const orc_real pose[6] = {0, 0, (orc_real)z, 0, 0, 0};
            const orc_real q[6] = {s, s, s, s, s, s};
            orc_real J[6][6], Fp[6][6];
            oracle_dq_dp(&og, pose, q, J);
            orc_constraint_jacobian(&og, pose, q, Fp);
            EXPECT_NEAR(f.nu, (double)orc_hadamard(Fp), IS_FLOAT ? 1e-4 : 1e-9);
            long double fro = 0, rows = 1, jtj = 0;
            for (int i = 0; i < 6; i++) {
                long double rn = 0;
                for (int j = 0; j < 6; j++)
                    rn += J[i][j] * J[i][j];
                fro += rn;
                rows *= sqrtl(rn);
            }
            for (int i = 0; i < 6; i++)
                for (int j = 0; j < 6; j++) {
                    long double e = 0;
                    for (int m = 0; m < 6; m++)
                        e += J[m][i] * J[m][j];
                    jtj += e * e;
                }
            const double det = (double)(orc_hadamard(J) * rows);
            double sum2 = 0, sum4 = 0, prod = 1;
            int has_sigma = 0;
            for (int m = 0; m < 6; m++) {
                const double inv = 1.0 / (double)f.sv[m];
                sum2 += inv * inv;
                sum4 += inv * inv * inv * inv;
                prod *= inv;
                if (m > 0)
                    assert_true(f.sv[m] <= f.sv[m - 1]);
                has_sigma |= fabs((double)f.sv[m] - sig) <= 10 * rel * sig;
            }
            EXPECT_NEAR(sum2, (double)fro, 10 * rel * (double)fro);
            EXPECT_NEAR(sum4, (double)jtj, 10 * rel * (double)jtj);
            EXPECT_NEAR(prod, det, 10 * rel * det);
            assert_true(has_sigma);
            /* Three-fold symmetry about the axis: (x, y) and (roll, pitch) turn alike, so their
             * four singular values come in two equal pairs; z and yaw stand alone. */
            int pairs = 0;
            for (int m = 0; m + 1 < 6; m++)
                if (fabs((double)(f.sv[m] - f.sv[m + 1])) <= 10 * rel * (double)f.sv[m]) {
                    ++pairs;
                    ++m;
                }
            if (pairs != 2) {
                print_error("%s, z = %g: singular values %g %g %g %g %g %g are not two pairs and two\n", d->name,
                            (double)z, (double)f.sv[0], (double)f.sv[1], (double)f.sv[2], (double)f.sv[3],
                            (double)f.sv[4], (double)f.sv[5]);
                fail();
            }
        }
        tse_vertical_figures f;
        EXPECT_STATUS(tse_vertical_profile(&g, (tse_real)(3.0 * (double)p.L), &f), TSE_UNREACHABLE);
        assert_true(isnan(f.sigma_z) && isnan(f.sv[0]) && isnan(f.mu_min) && isnan(f.nu));
        EXPECT_STATUS(tse_vertical_profile(&g, (tse_real)NAN, &f), TSE_INVALID);
        assert_true(isnan(f.sv[5]));
    }
}

/* Margins of random poses against the reference's branch solutions, wherever each scissor has
 * exactly one and no verdict is too close to call; a scissor without one is named. */
static void test_margins_oracle(void **state)
{
    (void)state;
    const int designs[] = {0, 4, 6};
    const orc_tol tol = test_orc_tol();
    const double mu_tol = IS_FLOAT ? 2e-4 : 1e-8, nu_tol = IS_FLOAT ? 2e-4 : 1e-8;
    uint64_t seed = 20260511;
    for (size_t n = 0; n < sizeof designs / sizeof designs[0]; n++) {
        const study_design *d = &study_designs[designs[n]];
        tse_params p = study_params(d);
        tse_geometry g;
        orc_geom og;
        test_geometries(&p, &g, &og);
        int compared = 0, unreachable = 0;
        for (int t = 0; t < 400; t++) {
            tse_real pose[6];
            set_pose(pose, rng_range(&seed, -0.5, 0.5), rng_range(&seed, -0.5, 0.5), rng_range(&seed, 0.1, 1.75),
                     rng_range(&seed, -0.3, 0.3), rng_range(&seed, -0.3, 0.3), rng_range(&seed, -0.6, 0.6));
            tse_margin_result m;
            const tse_status st = tse_margins(&g, pose, &m);
            assert_int_equal(st, m.status);
            orc_real po[6], C[3][3];
            pose_to_orc(pose, po);
            orc_joints(&og, po, C);
            orc_scissor_set set[3];
            int unsure = 0, first_missing = 0;
            for (int i = 0; i < 3; i++) {
                orc_scissor(&og, i, C[i], &tol, &set[i]);
                unsure |= set[i].near_boundary || set[i].n > 1;
                if (set[i].n == 0 && !first_missing)
                    first_missing = i + 1;
            }
            if (unsure)
                continue;
            ++compared;
            for (int i = 0; i < 3; i++) {
                if (set[i].n == 0) {
                    assert_true(isnan(m.mu[i]) && isnan(m.q[2 * i]));
                    continue;
                }
                EXPECT_NEAR(m.mu[i], (double)set[i].branch[0].mu, mu_tol);
                EXPECT_NEAR(m.q[2 * i], (double)set[i].branch[0].sa, IS_FLOAT ? 1e-4 : 1e-8);
                EXPECT_NEAR(m.q[2 * i + 1], (double)set[i].branch[0].sb, IS_FLOAT ? 1e-4 : 1e-8);
            }
            if (first_missing) {
                ++unreachable;
                EXPECT_STATUS(st, TSE_UNREACHABLE);
                assert_int_equal(m.scissor, first_missing);
                assert_true(isnan(m.nu));
                continue;
            }
            EXPECT_STATUS(st, TSE_OK);
            assert_int_equal(m.scissor, 0);
            orc_real q[6], Fp[6][6];
            for (int i = 0; i < 3; i++) {
                q[2 * i] = set[i].branch[0].sa;
                q[2 * i + 1] = set[i].branch[0].sb;
            }
            orc_constraint_jacobian(&og, po, q, Fp);
            EXPECT_NEAR(m.nu, (double)orc_hadamard(Fp), nu_tol);
        }
        print_message("margins, %s: %d poses compared with the reference, %d of them without a branch "
                      "solution for some scissor\n",
                      d->name, compared, unreachable);
        assert_true(compared > 200 && unreachable > 20 && compared - unreachable > 20);
    }
    tse_params p;
    tse_params_default(&p);
    tse_geometry g;
    assert_int_equal(tse_geometry_init(&g, &p), TSE_PARAM_OK);
    tse_margin_result m;
    const tse_real bad[6] = {0, 0, (tse_real)INFINITY, 0, 0, 0};
    EXPECT_STATUS(tse_margins(&g, bad, &m), TSE_INVALID);
    assert_true(isnan(m.mu[0]) && isnan(m.nu) && m.scissor >= 1 && m.scissor <= 3);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sigma_z_closed_form),
        cmocka_unit_test(test_haf),
        cmocka_unit_test(test_workspace_invalid),
        cmocka_unit_test(test_workspace_prototype),
        cmocka_unit_test(test_workspace_tilted),
        cmocka_unit_test(test_workspace_points_and_count),
        cmocka_unit_test(test_workspace_pose_invalid),
        cmocka_unit_test(test_workspace_cells_fill_cylinder),
        cmocka_unit_test(test_workspace_volume),
        cmocka_unit_test(test_workspace_designs_oracle),
        cmocka_unit_test(test_vertical_profile),
        cmocka_unit_test(test_margins_oracle),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
