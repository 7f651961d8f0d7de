/* Design parameters, their validation, the derived geometry, and the status / parameter names
 * (kinematics.md, "Design parameters", "Frames"). */
#include "test_common.h"

#if TSE_REAL_FLOAT
#define nextafter_real(x, up) nextafterf((x), (up) ? INFINITY : 0.0f)
#define sqrt_real sqrtf
#else
#define nextafter_real(x, up) nextafter((x), (up) ? INFINITY : 0.0)
#define sqrt_real sqrt
#endif

/* The prototype, from kinematics.md's table. */
static void test_default_is_prototype(void **state)
{
    (void)state;
    tse_params p;
    memset(&p, 0xA5, sizeof p);
    tse_params_default(&p);
    /* the literal in the working precision: exact in double, within one rounding in float */
    double e = IS_FLOAT ? 1e-7 : 1e-15;
    EXPECT_NEAR(p.L, 1.727, e * 1.727);
    EXPECT_NEAR(p.k1, 0.2647, e);
    EXPECT_NEAR(p.eta, 30.0 * 3.14159265358979323846 / 180.0, e);
    EXPECT_NEAR(p.k3, 0.0186, e);
    EXPECT_NEAR(p.k4, 0.11765, e);
    EXPECT_NEAR(p.alpha_min, asin(0.324 / 1.727), 4 * e);
    EXPECT_NEAR(p.alpha_max, asin(1.619 / 1.727), 4 * e);
    EXPECT_NEAR(p.s_min, 0.0, 0.0);
    EXPECT_NEAR(p.s_max, 0.90, e);
    EXPECT_NEAR(p.mu_min, 0.05, e);
    EXPECT_NEAR(p.nu_min, 1e-3, e * 1e-3);
    assert_int_equal(tse_params_check(&p), TSE_PARAM_OK);
}

/* One invalid value of one field. */
typedef struct {
    size_t offset;
    double value;
    tse_param_id id;
    const char *what;
} bad_value;

#define FIELD(f) offsetof(tse_params, f)

static void set_field(tse_params *p, size_t off, tse_real v)
{
    memcpy((char *)p + off, &v, sizeof v);
}

static void expect_rejected(const tse_params *p, tse_param_id want, const char *what)
{
    tse_param_id got = tse_params_check(p);
    if (got != want) {
        print_error("tse_params_check(%s) = %d (%s), expected %d (%s)\n", what, (int)got,
                    tse_param_name(got), (int)want, tse_param_name(want));
        fail();
    }
    /* tse_geometry_init reports the same parameter and leaves the geometry untouched */
    tse_geometry g, before;
    memset(&g, 0x5C, sizeof g);
    memcpy(&before, &g, sizeof g);
    got = tse_geometry_init(&g, p);
    if (got != want) {
        print_error("tse_geometry_init(%s) = %d (%s), expected %d (%s)\n", what, (int)got,
                    tse_param_name(got), (int)want, tse_param_name(want));
        fail();
    }
    if (memcmp(&g, &before, sizeof g) != 0) {
        print_error("tse_geometry_init(%s) modified the geometry on failure\n", what);
        fail();
    }
}

static void test_each_invalid_value_names_its_parameter(void **state)
{
    (void)state;
    const double deg = 3.14159265358979323846 / 180.0;
    const bad_value cases[] = {
        {FIELD(L), 0.0, TSE_PARAM_L, "L = 0"},
        {FIELD(L), -1.727, TSE_PARAM_L, "L < 0"},
        {FIELD(k1), 0.0, TSE_PARAM_K1, "k1 = 0"},
        {FIELD(k1), -0.2, TSE_PARAM_K1, "k1 < 0"},
        {FIELD(k1), 1.001, TSE_PARAM_K1, "k1 > 1"},
        {FIELD(eta), 91.0 * deg, TSE_PARAM_ETA, "eta = 91 deg"},
        {FIELD(eta), -91.0 * deg, TSE_PARAM_ETA, "eta = -91 deg"},
        {FIELD(eta), 3.0, TSE_PARAM_ETA, "eta = 3 rad"},
        {FIELD(eta), -2.0, TSE_PARAM_ETA, "eta = -2 rad"},
        {FIELD(k3), -0.001, TSE_PARAM_K3, "k3 < 0"},
        {FIELD(k4), 0.0, TSE_PARAM_K4, "k4 = 0"},
        {FIELD(k4), -0.1, TSE_PARAM_K4, "k4 < 0"},
        {FIELD(alpha_min), 0.0, TSE_PARAM_ALPHA_MIN, "alpha_min = 0"},
        {FIELD(alpha_min), -0.1, TSE_PARAM_ALPHA_MIN, "alpha_min < 0"},
        {FIELD(alpha_max), 91.0 * deg, TSE_PARAM_ALPHA_MAX, "alpha_max = 91 deg"},
        {FIELD(alpha_max), 2.0, TSE_PARAM_ALPHA_MAX, "alpha_max = 2 rad"},
        {FIELD(s_min), -0.001, TSE_PARAM_S_MIN, "s_min < 0"},
        {FIELD(mu_min), -0.01, TSE_PARAM_MU_MIN, "mu_min < 0"},
        {FIELD(mu_min), 1.0, TSE_PARAM_MU_MIN, "mu_min = 1"},
        {FIELD(nu_min), -1e-3, TSE_PARAM_NU_MIN, "nu_min < 0"},
        {FIELD(nu_min), 1.0, TSE_PARAM_NU_MIN, "nu_min = 1"},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        tse_params p;
        tse_params_default(&p);
        set_field(&p, cases[k].offset, (tse_real)cases[k].value);
        expect_rejected(&p, cases[k].id, cases[k].what);
    }
}

/* NaN, +inf and -inf are invalid in every field and name exactly that field, also where the
 * field takes part in an ordering rule with another one (alpha_max, s_max). */
static void test_non_finite_names_its_parameter(void **state)
{
    (void)state;
    const struct {
        size_t off;
        tse_param_id id;
        const char *name;
    } fields[] = {
        {FIELD(L), TSE_PARAM_L, "L"},
        {FIELD(k1), TSE_PARAM_K1, "k1"},
        {FIELD(eta), TSE_PARAM_ETA, "eta"},
        {FIELD(k3), TSE_PARAM_K3, "k3"},
        {FIELD(k4), TSE_PARAM_K4, "k4"},
        {FIELD(alpha_min), TSE_PARAM_ALPHA_MIN, "alpha_min"},
        {FIELD(alpha_max), TSE_PARAM_ALPHA_MAX, "alpha_max"},
        {FIELD(s_min), TSE_PARAM_S_MIN, "s_min"},
        {FIELD(s_max), TSE_PARAM_S_MAX, "s_max"},
        {FIELD(mu_min), TSE_PARAM_MU_MIN, "mu_min"},
        {FIELD(nu_min), TSE_PARAM_NU_MIN, "nu_min"},
    };
    const tse_real values[3] = {(tse_real)NAN, (tse_real)INFINITY, -(tse_real)INFINITY};
    const char *vname[3] = {"NaN", "+inf", "-inf"};
    for (size_t f = 0; f < sizeof fields / sizeof fields[0]; f++) {
        for (int v = 0; v < 3; v++) {
            tse_params p;
            tse_params_default(&p);
            set_field(&p, fields[f].off, values[v]);
            char what[64];
            snprintf(what, sizeof what, "%s = %s", fields[f].name, vname[v]);
            expect_rejected(&p, fields[f].id, what);
        }
    }
}

/* Rules that relate two parameters: either of the two may be named, but nothing else. */
static void test_ordering_rules(void **state)
{
    (void)state;
    struct {
        double amin, amax, smin, smax;
        tse_param_id a, b;
        const char *what;
    } cases[] = {
        {0.9, 0.8, 0.0, 0.9, TSE_PARAM_ALPHA_MIN, TSE_PARAM_ALPHA_MAX, "alpha_min > alpha_max"},
        {0.8, 0.8, 0.0, 0.9, TSE_PARAM_ALPHA_MIN, TSE_PARAM_ALPHA_MAX, "alpha_min = alpha_max"},
        {0.2, 1.2, 0.5, 0.4, TSE_PARAM_S_MIN, TSE_PARAM_S_MAX, "s_min > s_max"},
        {0.2, 1.2, 0.5, 0.5, TSE_PARAM_S_MIN, TSE_PARAM_S_MAX, "s_min = s_max"},
        {0.2, 1.2, 0.0, 0.0, TSE_PARAM_S_MIN, TSE_PARAM_S_MAX, "s_min = s_max = 0"},
        {0.2, 1.2, 0.0, -0.1, TSE_PARAM_S_MIN, TSE_PARAM_S_MAX, "s_max < 0 = s_min"},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        tse_params p;
        tse_params_default(&p);
        p.alpha_min = (tse_real)cases[k].amin;
        p.alpha_max = (tse_real)cases[k].amax;
        p.s_min = (tse_real)cases[k].smin;
        p.s_max = (tse_real)cases[k].smax;
        tse_param_id got = tse_params_check(&p);
        if (got != cases[k].a && got != cases[k].b) {
            print_error("%s: got %d (%s), expected %s or %s\n", cases[k].what, (int)got,
                        tse_param_name(got), tse_param_name(cases[k].a), tse_param_name(cases[k].b));
            fail();
        }
        tse_geometry g;
        assert_int_equal(tse_geometry_init(&g, &p), got);
    }
}

/* Values on the valid side of every rule are accepted. */
static void test_valid_edges_accepted(void **state)
{
    (void)state;
    const double deg = 3.14159265358979323846 / 180.0;
    struct {
        size_t off;
        double v;
        const char *what;
    } cases[] = {
        {FIELD(k1), 1.0, "k1 = 1"},
        {FIELD(eta), 0.0, "eta = 0"},
        {FIELD(eta), -30.0 * deg, "eta = -30 deg"},
        {FIELD(eta), 89.0 * deg, "eta = 89 deg"},
        {FIELD(k3), 0.0, "k3 = 0"},
        {FIELD(alpha_min), 1e-3, "alpha_min = 1e-3"},
        {FIELD(alpha_max), 89.0 * deg, "alpha_max = 89 deg"},
        {FIELD(s_max), 5.0, "s_max = 5"},
        {FIELD(mu_min), 0.0, "mu_min = 0"},
        {FIELD(mu_min), 0.99, "mu_min = 0.99"},
        {FIELD(nu_min), 0.0, "nu_min = 0"},
        {FIELD(L), 0.01, "L = 0.01"},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        tse_params p;
        tse_params_default(&p);
        set_field(&p, cases[k].off, (tse_real)cases[k].v);
        tse_param_id got = tse_params_check(&p);
        if (got != TSE_PARAM_OK) {
            print_error("%s rejected as %s\n", cases[k].what, tse_param_name(got));
            fail();
        }
        tse_geometry g;
        assert_int_equal(tse_geometry_init(&g, &p), TSE_PARAM_OK);
    }
}

/* The derived geometry follows kinematics.md's frames. */
static void test_geometry_frames(void **state)
{
    (void)state;
    tse_params p;
    tse_params_default(&p);
    tse_geometry g;
    assert_int_equal(tse_geometry_init(&g, &p), TSE_PARAM_OK);
    double e = IS_FLOAT ? 2e-6 : 1e-14;
    const double L = p.L, l0 = p.k1 * p.L;
    EXPECT_NEAR(g.l0, l0, e);
    EXPECT_NEAR(g.r_act, p.k3 * L, e);
    EXPECT_NEAR(g.r_top, p.k4 * L, e);
    EXPECT_NEAR(g.inv_r_top, 1.0 / (p.k4 * L), e * 10);
    double gg = (1.0 - (L / l0) * (L / l0)) / 4.0;
    EXPECT_NEAR(g.g, gg, e * 10);
    EXPECT_NEAR(g.c, cos(2.0 * p.eta), e);
    EXPECT_NEAR(g.w_lo, 2.0 * l0 * cos((double)p.alpha_max), e);
    EXPECT_NEAR(g.w_hi, 2.0 * l0 * cos((double)p.alpha_min), e);
    const double pi = 3.14159265358979323846;
    for (int i = 0; i < 3; i++) {
        double beta = i * 2.0 * pi / 3.0;
        double er[2] = {cos(beta), sin(beta)}, et[2] = {-sin(beta), cos(beta)};
        double ce = cos((double)p.eta), se = sin((double)p.eta);
        for (int k = 0; k < 2; k++) {
            EXPECT_NEAR(g.sc[i].er[k], er[k], e);
            EXPECT_NEAR(g.sc[i].o[k], p.k3 * L * er[k], e);
            EXPECT_NEAR(g.sc[i].a[k], ce * et[k] + se * er[k], e);
            EXPECT_NEAR(g.sc[i].b[k], -ce * et[k] + se * er[k], e);
        }
    }
    /* home: symmetric, zero orientation, every slide the vertical solution at its height */
    EXPECT_NEAR(g.home_pose[TSE_X], 0.0, 0.0);
    EXPECT_NEAR(g.home_pose[TSE_Y], 0.0, 0.0);
    EXPECT_NEAR(g.home_pose[TSE_ROLL], 0.0, 0.0);
    EXPECT_NEAR(g.home_pose[TSE_PITCH], 0.0, 0.0);
    EXPECT_NEAR(g.home_pose[TSE_YAW], 0.0, 0.0);
    assert_true(g.home_pose[TSE_Z] > 0);
    orc_geom og;
    orc_params op = test_orc_params(&p);
    orc_geom_init(&og, &op);
    EXPECT_NEAR(g.home_s, (double)orc_vertical_slide(&og, (orc_real)g.home_pose[TSE_Z]), TOL_Q);
    /* home lies inside the stroke */
    assert_true(g.home_s > p.s_min && g.home_s < p.s_max);
    assert_true(g.step_max > 0 && g.step_max < p.L);
}

/* The stops' band on w^2 (w_lo2, w_hi2) gives the verdict of sqrt(w^2) against w_lo, w_hi on
 * every value near its ends, for designs from tiny to huge: the solver checks one form, the
 * fallback the other. */
static void test_width_band_squared(void **state)
{
    (void)state;
    const double scales[] = {1.0, 1e-30, 1e-3, 7.3, 1e25};
    const double alphas[][2] = {{0.0, 0.0}, {0.01, 1.5}, {0.4, 0.41}, {1e-6, 1.5707}};
    int checked = 0;
    for (size_t s = 0; s < sizeof scales / sizeof scales[0]; s++) {
        for (size_t a = 0; a < sizeof alphas / sizeof alphas[0]; a++) {
            tse_params p;
            tse_params_default(&p);
            p.L = (tse_real)(p.L * scales[s]);
            p.s_min = (tse_real)(p.s_min * scales[s]);
            p.s_max = (tse_real)(p.s_max * scales[s]);
            if (alphas[a][1] > 0.0) {
                p.alpha_min = (tse_real)alphas[a][0];
                p.alpha_max = (tse_real)alphas[a][1];
            }
            tse_geometry g;
            assert_int_equal(tse_geometry_init(&g, &p), TSE_PARAM_OK);
            const tse_real ends[2] = {g.w_lo * g.w_lo, g.w_hi * g.w_hi};
            for (int e = 0; e < 2; e++) {
                tse_real x = ends[e];
                for (int k = 0; k < 64; k++)
                    x = nextafter_real(x, 0);
                for (int k = 0; k < 128; k++, x = nextafter_real(x, 1)) {
                    const tse_real w = sqrt_real(x);
                    if ((x >= g.w_lo2) != (w >= g.w_lo) || (x <= g.w_hi2) != (w <= g.w_hi)) {
                        print_error("L %g alpha %g..%g: w^2 %.17g (w %.17g) against [%.17g, %.17g] and "
                                    "[%.17g, %.17g]\n",
                                    (double)p.L, (double)p.alpha_min, (double)p.alpha_max, (double)x, (double)w,
                                    (double)g.w_lo2, (double)g.w_hi2, (double)g.w_lo, (double)g.w_hi);
                        fail();
                    }
                    checked++;
                }
            }
        }
    }
    assert_int_equal(checked, 5 * 4 * 2 * 128);
}

static void test_names(void **state)
{
    (void)state;
    const char *pnames[TSE_PARAM_COUNT] = {NULL,        "L",         "k1",    "eta",
                                           "k3",        "k4",        "alpha_min", "alpha_max",
                                           "s_min",     "s_max",     "mu_min", "nu_min"};
    for (int id = 1; id < TSE_PARAM_COUNT; id++)
        assert_string_equal(tse_param_name((tse_param_id)id), pnames[id]);
    assert_string_equal(tse_param_name(TSE_PARAM_COUNT), "?");
    assert_string_equal(tse_param_name((tse_param_id)-1), "?");
    assert_string_equal(tse_param_name((tse_param_id)1000), "?");

    const char *snames[TSE_STATUS_COUNT] = {"ok",    "invalid", "unreachable", "below",
                                            "alpha", "stroke",  "singular",    "degenerate",
                                            "noconverge"};
    for (int s = 0; s < TSE_STATUS_COUNT; s++) {
        assert_string_equal(tse_status_name((tse_status)s), snames[s]);
        tse_status back = TSE_STATUS_COUNT;
        assert_int_equal(tse_status_parse(snames[s], &back), 0);
        assert_int_equal(back, s);
        /* round trip through the name */
        back = TSE_STATUS_COUNT;
        assert_int_equal(tse_status_parse(tse_status_name((tse_status)s), &back), 0);
        assert_int_equal(back, s);
    }
    assert_string_equal(tse_status_name(TSE_STATUS_COUNT), "?");
    assert_string_equal(tse_status_name((tse_status)-1), "?");
    assert_string_equal(tse_status_name((tse_status)77), "?");
    tse_status out = TSE_OK;
    assert_int_equal(tse_status_parse("bogus", &out), -1);
    assert_int_equal(tse_status_parse("", &out), -1);
    assert_int_equal(tse_status_parse("?", &out), -1);
    assert_int_equal(tse_status_parse("ok ", &out), -1);
    assert_int_equal(tse_status_parse("unreach", &out), -1);
    assert_int_equal(tse_status_parse("noconvergence", &out), -1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_default_is_prototype),
        cmocka_unit_test(test_each_invalid_value_names_its_parameter),
        cmocka_unit_test(test_non_finite_names_its_parameter),
        cmocka_unit_test(test_ordering_rules),
        cmocka_unit_test(test_valid_edges_accepted),
        cmocka_unit_test(test_geometry_frames),
        cmocka_unit_test(test_width_band_squared),
        cmocka_unit_test(test_names),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
