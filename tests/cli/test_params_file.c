/* tse-kin's parameter file (host_tools/params/kin_params_file.h) and its template (params_template.h):
 * defaults, SI names and degrees, the controller's names, comments, a BOM, and an error naming the
 * file and line for every kind of mistake.  Expected values are the prototype of
 * docs/kinematics.md, the controller's table and hand conversions, not the parser's output. */
#define _POSIX_C_SOURCE 200809L /* fmemopen, mkstemp, open_memstream */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "fw/params.h"
#include "kin_params_file.h"
#include "param_text.h"
#include "params_template.h"

#define PI 3.14159265358979323846

static void assert_close(double got, double want, double rel)
{
    if (!(fabs(got - want) <= rel * fabs(want)))
        fail_msg("got %.17g, want %.17g (relative %g)", got, want, rel);
}

static void assert_contains(const char *s, const char *fragment)
{
    if (!strstr(s, fragment))
        fail_msg("'%s' does not contain '%s'", s, fragment);
}

static kin_param_values parse_as(kin_params_judge judge, const char *text)
{
    kin_param_values p;
    kin_params_default(&p);
    char err[512] = "";
    const kin_params_outcome r = kin_params_parse(text, "f.params", judge, &p, err, sizeof err);
    if (r != KIN_PARAMS_OK)
        fail_msg("'%s' refused as a %s: %s", text, judge == KIN_PARAMS_DESIGN ? "design" : "controller's set", err);
    return p;
}

/* Taken as a design and as a controller's set alike, with the same values. */
static kin_param_values parse_ok(const char *text)
{
    const kin_param_values p = parse_as(KIN_PARAMS_DESIGN, text);
    const kin_param_values q = parse_as(KIN_PARAMS_CONTROLLER, text);
    assert_memory_equal(&p, &q, sizeof p);
    return p;
}

/* The text is refused as `judge` says, the message contains every fragment, and nothing was
 * half-applied. */
static void refuse_as(kin_params_judge judge, const char *text, const char *fragment1, const char *fragment2)
{
    kin_param_values p, before;
    kin_params_default(&p);
    before = p;
    char err[512] = "";
    if (kin_params_parse(text, "f.params", judge, &p, err, sizeof err) != KIN_PARAMS_BAD)
        fail_msg("'%s' accepted as a %s", text, judge == KIN_PARAMS_DESIGN ? "design" : "controller's set");
    assert_contains(err, fragment1);
    if (fragment2)
        assert_contains(err, fragment2);
    assert_memory_equal(&p, &before, sizeof p);
}

/* Refused both ways: what the reader itself refuses (lines, keys, numbers, repeats). */
static void expect_error(const char *text, const char *fragment1, const char *fragment2)
{
    refuse_as(KIN_PARAMS_CONTROLLER, text, fragment1, fragment2);
    refuse_as(KIN_PARAMS_DESIGN, text, fragment1, fragment2);
}

static void test_defaults_are_the_prototype(void **state)
{
    (void)state;
    kin_param_values p;
    kin_params_default(&p);
    /* kinematics.md, "Design parameters". */
    assert_close(p.v[TSE_PARAM_L], 1.727, 1e-15);
    assert_close(p.v[TSE_PARAM_K1], 0.2647, 1e-15);
    assert_close(p.v[TSE_PARAM_ETA], PI / 6, 1e-15);
    assert_close(p.v[TSE_PARAM_K3], 0.0186, 1e-15);
    assert_close(p.v[TSE_PARAM_K4], 0.11765, 1e-15);
    assert_close(p.v[TSE_PARAM_ALPHA_MIN], asin(0.324 / 1.727), 1e-15);
    assert_close(p.v[TSE_PARAM_ALPHA_MAX], asin(1.619 / 1.727), 1e-15);
    assert_true(p.v[TSE_PARAM_S_MIN] == 0.0);
    assert_close(p.v[TSE_PARAM_S_MAX], 0.90, 1e-15);
    assert_close(p.v[TSE_PARAM_MU_MIN], 0.05, 1e-15);
    assert_close(p.v[TSE_PARAM_NU_MIN], 1e-3, 1e-15);
    for (int i = 0; i < TSE_PARAM_COUNT; ++i)
        assert_int_equal(p.line[i], 0);

    /* An empty file, or one of comments only, is the prototype. */
    kin_param_values q = parse_ok("");
    assert_memory_equal(&q, &p, sizeof p);
    q = parse_ok("# nothing but a comment\n\n   \t\n#\n");
    assert_memory_equal(&q, &p, sizeof p);
}

static void test_degrees_and_units(void **state)
{
    (void)state;
    const kin_param_values p = parse_as(KIN_PARAMS_DESIGN, "eta_deg = 45\nalpha_min_deg = 10\nalpha_max_deg = 70\nL = 2\ns_max = 0.5\n");
    assert_close(p.v[TSE_PARAM_ETA], PI / 4, 1e-15);
    assert_close(p.v[TSE_PARAM_ALPHA_MIN], 10 * PI / 180, 1e-15);
    assert_close(p.v[TSE_PARAM_ALPHA_MAX], 70 * PI / 180, 1e-15);
    assert_true(p.v[TSE_PARAM_L] == 2.0); /* lengths are not converted */
    assert_true(p.v[TSE_PARAM_S_MAX] == 0.5);
    const kin_param_values n = parse_as(KIN_PARAMS_DESIGN, "eta_deg = -30\n");
    assert_close(n.v[TSE_PARAM_ETA], -PI / 6, 1e-15);
    /* The SI names take radians, unconverted. */
    const kin_param_values r = parse_as(KIN_PARAMS_DESIGN, "eta = 0.5\nalpha_min = 0.2\nalpha_max = 1.25\n");
    assert_true(r.v[TSE_PARAM_ETA] == 0.5);
    assert_true(r.v[TSE_PARAM_ALPHA_MIN] == 0.2);
    assert_true(r.v[TSE_PARAM_ALPHA_MAX] == 1.25);
    assert_int_equal(r.line[TSE_PARAM_ALPHA_MAX], 3);
    /* The two spellings may be mixed across parameters. */
    const kin_param_values m = parse_as(KIN_PARAMS_DESIGN, "eta = -0.25\nalpha_min_deg = 15\n");
    assert_true(m.v[TSE_PARAM_ETA] == -0.25);
    assert_close(m.v[TSE_PARAM_ALPHA_MIN], PI / 12, 1e-15);
}

static void test_both_spellings_of_one_parameter(void **state)
{
    (void)state;
    expect_error("eta = 0.5\nL = 2\neta_deg = 30\n", "f.params:3: eta_deg given twice (first on line 1 as eta)",
                 NULL);
    expect_error("alpha_max_deg = 60\nalpha_max = 1\n",
                 "f.params:2: alpha_max given twice (first on line 1 as alpha_max_deg)", NULL);
    expect_error("alpha_min = 0.2\n# c\nALPHA_MIN_deg = 11.4\n",
                 "f.params:3: ALPHA_MIN_deg given twice (first on line 1 as alpha_min)", NULL);
    expect_error("eta = 0.5\neta = 0.5\n", "f.params:2: eta given twice (first on line 1 as eta)", NULL);
}

/* The controller's table (fw_param_table) names the parameters: its kinematic names are the
 * library's, and every other name is accepted and ignored. */
static void test_controller_names(void **state)
{
    (void)state;
    for (int id = 1; id < TSE_PARAM_COUNT; ++id)
        assert_string_equal(fw_param_table[FP_L + id - 1].name, tse_param_name((tse_param_id)id));
    kin_param_values d;
    kin_params_default(&d);
    int others = 0;
    for (int i = 0; i < FP_COUNT; ++i) {
        const char *name = fw_param_table[i].name;
        const int kinematic = i < TSE_PARAM_COUNT - 1;
        assert_int_equal(kin_param_is_controller_only(name), !kinematic);
        if (kinematic)
            continue;
        ++others;
        /* The default, in SI (the template's value): valid, and ignored by tse-kin. */
        char text[128];
        param_key k;
        param_si_key(i, &k);
        snprintf(text, sizeof text, "# SI\n%s = %.17g  # its default\n", name, fw_param_table[i].def / k.per_unit);
        kin_param_values p = parse_ok(text);
        assert_memory_equal(p.v, d.v, sizeof p.v); /* nothing kinematic changes */
        snprintf(text, sizeof text, "L = 2\n%s = fast\n", name);
        char want[96];
        snprintf(want, sizeof want, "f.params:2: %s: 'fast' is not one finite number", name);
        expect_error(text, want, NULL);
        snprintf(text, sizeof text, "k1 = 0.3\n%s = nan\n", name);
        expect_error(text, "f.params:2: ", "is not one finite number");
        snprintf(text, sizeof text, "%s = %.17g\n\n%s = 1\n", name, fw_param_table[i].def / k.per_unit, name);
        snprintf(want, sizeof want, "f.params:3: %s given twice (first on line 1 as %s)", name, name);
        expect_error(text, want, NULL);
    }
    assert_true(others >= 20); /* steps_per_m, slide_vmax ... can_kbps */
    /* A whole file of both kinds. */
    const kin_param_values p =
        parse_as(KIN_PARAMS_DESIGN, "L = 2\nslide_vmax = 0.15\nwatchdog_ms = 500\ncan_kbps = 500\nhome_sw_6 = 0.2\n");
    assert_true(p.v[TSE_PARAM_L] == 2.0);
    /* Names outside the table, or with a unit suffix the scheme does not give them, are unknown;
     * the table's names in another case are the same names (param_lookup's one case rule). */
    expect_error("slide_vmax_mm = 150\n", "f.params:1: unknown parameter 'slide_vmax_mm'", NULL);
    expect_error("L_mm = 1727\n", "f.params:1: unknown parameter 'L_mm'", NULL);
    parse_ok("Watchdog_ms = 500\nSTEPS_PER_M = 1280000\n");
    assert_true(kin_param_is_controller_only("Slide_Vmax"));
    assert_false(kin_param_is_controller_only("L"));
    assert_false(kin_param_is_controller_only("eta_deg"));
    assert_false(kin_param_is_controller_only("bogus"));
}

static void test_bom(void **state)
{
    (void)state;
    const kin_param_values p = parse_as(KIN_PARAMS_DESIGN, "\xEF\xBB\xBFL = 2.5\r\nk1 = 0.3\r\n");
    assert_true(p.v[TSE_PARAM_L] == 2.5);
    assert_int_equal(p.line[TSE_PARAM_L], 1);
    assert_int_equal(p.line[TSE_PARAM_K1], 2);
    /* Only at the start. */
    expect_error("L = 2.5\n\xEF\xBB\xBFk1 = 0.3\n", "f.params:2: unknown parameter", NULL);
}

/* The template reads back to the defaults exactly, sets every key once in SI, and says units. */
static void test_template(void **state)
{
    (void)state;
    char *text = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&text, &len);
    assert_non_null(f);
    kin_params_write_template(f);
    fclose(f);
    kin_param_values d, p;
    kin_params_default(&d);
    kin_params_default(&p);
    p.v[TSE_PARAM_L] = 3.0; /* so that reading the template must set it back */
    char err[512] = "";
    if (kin_params_parse(text, "template", KIN_PARAMS_CONTROLLER, &p, err, sizeof err) != KIN_PARAMS_OK)
        fail_msg("the template is refused: %s", err);
    for (int id = 1; id < TSE_PARAM_COUNT; ++id) {
        if (p.v[id] != d.v[id])
            fail_msg("%s reads back as %.17g, default %.17g", tse_param_name((tse_param_id)id), p.v[id], d.v[id]);
        assert_true(p.line[id] > 0);   /* set by the template, not kept */
        assert_int_equal(p.degrees[id], 0); /* in SI */
    }
    /* Every name of the controller's table, once, at the start of a line. */
    for (int i = 0; i < FP_COUNT; ++i) {
        char key[48];
        snprintf(key, sizeof key, "\n%s = ", fw_param_table[i].name);
        const char *at = strstr(text, key);
        if (!at)
            fail_msg("the template has no '%s'", key + 1);
        assert_null(strstr(at + 1, key));
    }
    assert_null(strstr(text, "_deg = "));
    /* Units in the comments: radians with degrees beside them, metres, the controller's in SI. */
    assert_non_null(strstr(text, "\neta = 0.52359877559829"));
    assert_non_null(strstr(text, "# rad (30 deg); "));
    assert_non_null(strstr(text, "\nL = 1.727   # m; "));
    assert_non_null(strstr(text, "\nk1 = 0.2647   # ratio; "));
    assert_non_null(strstr(text, "\nslide_vmax = 0.15   # m/s; "));      /* 150000 um/s */
    assert_non_null(strstr(text, "\nplate_wmax = 0.5   # rad/s; "));     /* 500000 urad/s */
    assert_non_null(strstr(text, "\nwatchdog_ms = 500   # ms; "));
    assert_non_null(strstr(text, "\nhome_sw_1 = 0.2   # m; "));          /* 200000 um */
    assert_non_null(strstr(text, "range 0.001..2\n"));                   /* slide_vmax: 1000..2000000 um/s */
    free(text);
}

static void test_comments_blanks_crlf_and_lines(void **state)
{
    (void)state;
    const char *text = "# a design\r\n"
                       "\r\n"
                       "L = 2.0   # metres, trailing comment\r\n"
                       "\tk1=0.3#no spaces\n"
                       "   k3   =   0.02   \n"
                       "mu_min = 0.1"; /* no newline at the end */
    const kin_param_values p = parse_as(KIN_PARAMS_DESIGN, text);
    assert_true(p.v[TSE_PARAM_L] == 2.0);
    assert_true(p.v[TSE_PARAM_K1] == 0.3);
    assert_true(p.v[TSE_PARAM_K3] == 0.02);
    assert_true(p.v[TSE_PARAM_MU_MIN] == 0.1);
    assert_int_equal(p.line[TSE_PARAM_L], 3);
    assert_int_equal(p.line[TSE_PARAM_K1], 4);
    assert_int_equal(p.line[TSE_PARAM_K3], 5);
    assert_int_equal(p.line[TSE_PARAM_MU_MIN], 6);
    /* Keys not in the file keep the prototype's values and no line. */
    assert_close(p.v[TSE_PARAM_K4], 0.11765, 1e-15);
    assert_int_equal(p.line[TSE_PARAM_K4], 0);
}

static void test_syntax_errors_name_the_line(void **state)
{
    (void)state;
    expect_error("L = 1.7\nbogus = 3\n", "f.params:2: unknown parameter 'bogus'", NULL);
    expect_error("eta_rad = 0.5\n", "f.params:1: unknown parameter 'eta_rad'", NULL);
    /* radians: outside the controller's range; not a valid design */
    refuse_as(KIN_PARAMS_CONTROLLER, "eta = 30\n", "f.params:1: eta = 30 rad is outside -1.570796..1.570796 rad", NULL);
    refuse_as(KIN_PARAMS_DESIGN, "eta = 30\n", "f.params:1: eta = 30 is invalid (needs -pi/2 < eta < pi/2)", NULL);
    expect_error("alpha min_deg = 10\n", "f.params:1: unknown parameter", NULL);
    expect_error("= 3\n", "f.params:1: no parameter name before '='", NULL);
    expect_error("\n\nL 1.7\n", "f.params:3: expected 'name = value'", NULL);
    expect_error("k1 = 0.3\n# comment\nk1 = 0.4\n", "f.params:3: k1 given twice", "first on line 1");
    expect_error("eta_deg = 30\r\neta_deg = 30\r\n", "f.params:2: eta_deg given twice", NULL);
    /* Keys in any case, as the controller's reader takes them: l is L. */
    const kin_param_values p = parse_as(KIN_PARAMS_DESIGN, "l = 1.7\nETA_DEG = 45\n");
    assert_true(p.v[TSE_PARAM_L] == 1.7);
    assert_close(p.v[TSE_PARAM_ETA], PI / 4, 1e-15);
    assert_int_equal(p.degrees[TSE_PARAM_ETA], 1);
}

static void test_value_errors_name_the_line(void **state)
{
    (void)state;
    static const char *const bad[] = {
        "k3 = 0.01x\n", "k3 =\n", "k3 = # nothing\n", "k3 = nan\n", "k3 = inf\n", "k3 = -inf\n",
        "k3 = 1e999\n", "k3 = 0,02\n", "k3 = 0.01 0.02\n", "k3 = 0.01 = 0.02\n", "k3 = x\n", "k3 = 1e\n",
        "k3 = 1e-400\n", /* underflow: not taken as 0 */
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        char text[64];
        snprintf(text, sizeof text, "L = 1.727\n%s", bad[i]);
        expect_error(text, "f.params:2: k3: '", "' is not one finite number");
    }
    /* A long line is only a line: its value counts. */
    char text[2048];
    memset(text, ' ', sizeof text);
    memcpy(text, "# one\nL = 1.7", 14);
    strcpy(text + sizeof text - 2, "\n");
    const kin_param_values p = parse_ok(text);
    assert_true(p.v[TSE_PARAM_L] == 1.7);
    assert_int_equal(p.line[TSE_PARAM_L], 2);
}

/* Every rule of kinematics.md, "Valid parameter sets": the error names the key and its line. */
static void test_invalid_sets_name_the_line(void **state)
{
    (void)state;
    /* Each value's range (the controller's table, as written) and each rule of the set (the
     * controller's judge), named at the line that breaks it. */
    static const struct {
        const char *line;
        const char *want;
    } cases[] = {
        {"L = 0", "L = 0 m is outside 0.1..10 m"},
        {"L = -1", "L = -1 m is outside 0.1..10 m"},
        {"k1 = 0", "k1 = 0 is outside 0.000001..1"},
        {"k1 = 1.5", "k1 = 1.5 is outside 0.000001..1"},
        {"k1 = 1.0000004", "k1 = 1.0000004 is outside 0.000001..1"}, /* 1 ppm once rounded: refused as written */
        {"eta_deg = 90", "eta = 90 deg is outside -89.99998..89.99998 deg"},   /* 1570796 urad */
        {"eta_deg = -90", "eta = -90 deg is outside -89.99998..89.99998 deg"},
        {"eta = 1.5708", "eta = 1.5708 rad is outside -1.570796..1.570796 rad"}, /* just above pi/2 */
        {"eta = -1.5708", "eta = -1.5708 rad is outside"},
        {"alpha_min = 0", "alpha_min = 0 rad is outside 0.000001..1.570796 rad"},
        {"alpha_max = 1.5708", "alpha_max = 1.5708 rad is outside"},
        /* below the default alpha_min, asin(0.324 / 1.727) = 0.188727 rad */
        {"alpha_max = 0.1", "alpha_min = 0.188727 rad must be below alpha_max = 0.1 rad"},
        {"k3 = -0.01", "k3 = -0.01 is outside 0..1"},
        {"k4 = 0", "k4 = 0 is outside 0.000001..1"},
        {"alpha_min_deg = 0", "alpha_min = 0 deg is outside 0.00006..89.99998 deg"}, /* 1 urad = 5.7e-5 deg */
        {"alpha_max_deg = 90", "alpha_max = 90 deg is outside"},
        {"alpha_max_deg = 5", "alpha_min = 0.188727 rad must be below alpha_max = 0.087266 rad"},
        {"s_min = -0.1", "s_min = -0.1 m is outside 0..5 m"},
        {"s_max = 0", "s_max = 0 m is outside 0.000001..5 m"},
        {"mu_min = 1", "mu_min = 1 is outside 0..0.999999"},
        {"mu_min = -0.5", "mu_min = -0.5 is outside"},
        {"nu_min = 1", "nu_min = 1 is outside"},
        {"nu_min = -1e-3", "nu_min = -1e-3 is outside"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        char text[96], want[160];
        snprintf(text, sizeof text, "# design\n\n%s\n", cases[i].line);
        snprintf(want, sizeof want, "f.params:3: %s", cases[i].want);
        refuse_as(KIN_PARAMS_CONTROLLER, text, want, NULL);
    }
    /* Valid at the edges the rules allow. */
    parse_as(KIN_PARAMS_CONTROLLER, "k3 = 0\ns_min = 0\nmu_min = 0\nnu_min = 0\n");
    /* A pair out of order is named at the line of the pair's second key. */
    refuse_as(KIN_PARAMS_CONTROLLER, "s_max = 0.4\ns_min = 0.5\n", "f.params:1: s_min = 0.5 m must be below s_max = 0.4 m", NULL);
    refuse_as(KIN_PARAMS_CONTROLLER, "s_min = 0.5\ns_max = 0.4\n", "f.params:2: s_min = 0.5 m must be below s_max = 0.4 m", NULL);
    /* A key the file did not set is said to be its default: alpha_max = asin(1.619 / 1.727) =
     * 1.215271 rad, s_max = 0.9 m. */
    refuse_as(KIN_PARAMS_CONTROLLER, "alpha_min_deg = 80 # above the prototype's alpha_max (69.6 deg)\n",
                 "f.params: alpha_min = 1.396263 rad must be below alpha_max = 1.215271 rad",
                 "(alpha_max is not set in the file: its default is what is in conflict)");
    refuse_as(KIN_PARAMS_CONTROLLER, "s_min = 1.2\n", "f.params: s_min = 1.2 m must be below s_max = 0.9 m", "its default");
    /* The controller's rules of the whole set hold for tse-kin too: a rigid scissor (k1 = 1) cannot
     * reach the default homing switches (0.2 m): its alpha_max stop keeps each scissor at least
     * 2 l0 cos(alpha_max) = 2 x 1.727 x 1.619 / 1.727... wide. */
    refuse_as(KIN_PARAMS_CONTROLLER, "k1 = 1\n", "f.params: home_sw_1 = 0.2 m: the six homing switches cannot be reached together", NULL);
}


/* Every rule of kinematics.md, "Valid parameter sets", for a file read as a design: the error names
 * the key, in the spelling used, and its line; beyond the controller's ranges is no error. */
static void test_invalid_designs_name_the_line(void **state)
{
    (void)state;
    static const struct {
        const char *line;
        const char *key;
    } cases[] = {
        {"L = 0", "L"},
        {"L = -1", "L"},
        {"k1 = 0", "k1"},
        {"k1 = 1.5", "k1"},
        {"k1 = 1.0000004", "k1"},
        {"eta_deg = 90", "eta_deg"},
        {"eta_deg = -90", "eta_deg"},
        {"eta = 1.5708", "eta"}, /* just above pi/2 */
        {"eta = -1.5708", "eta"},
        {"alpha_min = 0", "alpha_min"},
        {"alpha_max = 1.5708", "alpha_max"},
        {"alpha_max = 0.1", "alpha_max"}, /* below the default alpha_min (0.1888 rad) */
        {"k3 = -0.01", "k3"},
        {"k4 = 0", "k4"},
        {"alpha_min_deg = 0", "alpha_min_deg"},
        {"alpha_max_deg = 90", "alpha_max_deg"},
        {"alpha_max_deg = 5", "alpha_max_deg"}, /* below the default alpha_min (10.8 deg) */
        {"s_min = -0.1", "s_min"},
        {"s_max = 0", "s_max"}, /* not above the default s_min = 0 */
        {"mu_min = 1", "mu_min"},
        {"mu_min = -0.5", "mu_min"},
        {"nu_min = 1", "nu_min"},
        {"nu_min = -1e-3", "nu_min"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        char text[96], want[64];
        snprintf(text, sizeof text, "# design\n\n%s\n", cases[i].line);
        snprintf(want, sizeof want, "f.params:3: %s = ", cases[i].key);
        refuse_as(KIN_PARAMS_DESIGN, text, want, "is invalid");
    }
    /* Valid at the edges the rules allow, and far beyond the controller's ranges. */
    parse_as(KIN_PARAMS_DESIGN, "k1 = 1\nk3 = 0\ns_min = 0\nmu_min = 0\nnu_min = 0\n");
    const kin_param_values big = parse_as(KIN_PARAMS_DESIGN, "L = 1e39\nwatchdog_ms = -7\n");
    assert_true(big.v[TSE_PARAM_L] == 1e39);
    /* The first key of the set that fails is named at the line that set it. */
    refuse_as(KIN_PARAMS_DESIGN, "s_max = 0.4\ns_min = 0.5\n", "f.params:1: s_max = 0.4 is invalid", NULL);
    refuse_as(KIN_PARAMS_DESIGN, "s_min = 0.5\ns_max = 0.4\n", "f.params:2: s_max = 0.4 is invalid", NULL);
    /* A key the file did not set is called the default value, by its SI name, angles also in
     * degrees: asin(1.619 / 1.727) = 1.2152711 rad = 69.629907 deg. */
    refuse_as(KIN_PARAMS_DESIGN, "alpha_min_deg = 80 # above the prototype's alpha_max (69.6 deg)\n",
              "f.params: default value alpha_max = 1.2152711", "(69.629907");
    refuse_as(KIN_PARAMS_DESIGN, "s_min = 1.2\n", "f.params: default value s_max = 0.9", "is invalid");
}

/* The SI key is the library's name; the angles, and only they, also have a _deg spelling. */
static void test_keys_follow_the_library_names(void **state)
{
    (void)state;
    const kin_param_key_def *keys;
    const int n = kin_param_keys(&keys);
    int si = 0, deg = 0;
    for (int id = 1; id < TSE_PARAM_COUNT; ++id)
        assert_string_equal(kin_param_key((tse_param_id)id), tse_param_name((tse_param_id)id));
    for (int i = 0; i < n; ++i) {
        const char *lib = tse_param_name(keys[i].id);
        const int angle = keys[i].id == TSE_PARAM_ETA || keys[i].id == TSE_PARAM_ALPHA_MIN ||
                          keys[i].id == TSE_PARAM_ALPHA_MAX;
        char want[32];
        snprintf(want, sizeof want, "%s%s", lib, keys[i].degrees ? "_deg" : "");
        assert_string_equal(keys[i].key, want);
        assert_string_equal(keys[i].unit, keys[i].degrees ? "deg" : angle ? "rad" : keys[i].unit);
        assert_true(!keys[i].degrees || angle);
        si += !keys[i].degrees;
        deg += keys[i].degrees;
    }
    assert_int_equal(si, TSE_PARAM_COUNT - 1);
    assert_int_equal(deg, 3);
}

static void test_describe_invalid(void **state)
{
    (void)state;
    kin_param_values p = parse_as(KIN_PARAMS_DESIGN, "L = 1.7\neta_deg = 89.99998\n");
    char err[512];
    kin_params_describe_invalid(&p, TSE_PARAM_ETA, "d.params", " in float precision", err, sizeof err);
    assert_contains(err, "d.params:2: eta_deg = 89.99998 is invalid in float precision");
    kin_params_describe_invalid(&p, TSE_PARAM_K4, "d.params", "", err, sizeof err);
    assert_contains(err, "d.params: default value k4 = 0.11765 is invalid");
    /* In the spelling the file used. */
    p = parse_as(KIN_PARAMS_DESIGN, "eta = 1.5\n");
    kin_params_describe_invalid(&p, TSE_PARAM_ETA, "d.params", " in float precision", err, sizeof err);
    assert_contains(err, "d.params:1: eta = 1.5 is invalid in float precision (needs -pi/2 < eta < pi/2)");
}

static void test_file(void **state)
{
    (void)state;
    kin_param_values p;
    kin_params_default(&p);
    char err[512] = "";
    assert_int_equal(kin_params_load("/nonexistent/tse.params", KIN_PARAMS_CONTROLLER, &p, err, sizeof err), KIN_PARAMS_UNREADABLE);
    assert_contains(err, "/nonexistent/tse.params: cannot open");

    char path[] = "/tmp/tse_params_XXXXXX";
    const int fd = mkstemp(path);
    assert_true(fd >= 0);
    const char content[] = "L = 1.8\nbad line\n";
    assert_int_equal(write(fd, content, sizeof content - 1), (int)(sizeof content - 1));
    close(fd);
    kin_params_default(&p);
    assert_int_equal(kin_params_load(path, KIN_PARAMS_CONTROLLER, &p, err, sizeof err), KIN_PARAMS_BAD);
    char want[64];
    snprintf(want, sizeof want, "%s:2: expected 'name = value'", path);
    assert_contains(err, want);

    /* A NUL would hide the rest of the file from a string parser: refused, as not a text file. */
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    static const char nul[] = "k1 = 0.3\n\0k1 = 0.4\n";
    assert_int_equal(fwrite(nul, 1, sizeof nul - 1, f), sizeof nul - 1);
    fclose(f);
    assert_int_equal(kin_params_load(path, KIN_PARAMS_CONTROLLER, &p, err, sizeof err), KIN_PARAMS_BAD);
    assert_contains(err, "contains a NUL byte");
    unlink(path);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_defaults_are_the_prototype),
        cmocka_unit_test(test_degrees_and_units),
        cmocka_unit_test(test_both_spellings_of_one_parameter),
        cmocka_unit_test(test_controller_names),
        cmocka_unit_test(test_bom),
        cmocka_unit_test(test_template),
        cmocka_unit_test(test_comments_blanks_crlf_and_lines),
        cmocka_unit_test(test_syntax_errors_name_the_line),
        cmocka_unit_test(test_value_errors_name_the_line),
        cmocka_unit_test(test_invalid_sets_name_the_line),
        cmocka_unit_test(test_invalid_designs_name_the_line),
        cmocka_unit_test(test_keys_follow_the_library_names),
        cmocka_unit_test(test_describe_invalid),
        cmocka_unit_test(test_file),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
