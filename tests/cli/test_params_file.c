/* tse-kin's parameter file (host_tools/tse_kin/params_file.h): defaults, degrees, comments, and an
 * error naming the file and line for every kind of mistake.  Expected values are the prototype of
 * kinematics.md and hand conversions, not the parser's output. */
#define _POSIX_C_SOURCE 200809L /* fmemopen, mkstemp */
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

#include "params_file.h"

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

static kin_param_values parse_ok(const char *text)
{
    kin_param_values p;
    kin_params_default(&p);
    char err[512] = "";
    const kin_params_outcome r = kin_params_parse(text, "f.params", &p, err, sizeof err);
    if (r != KIN_PARAMS_OK)
        fail_msg("'%s' refused: %s", text, err);
    return p;
}

/* The text is refused, the message contains every fragment, and nothing was half-applied. */
static void expect_error(const char *text, const char *fragment1, const char *fragment2)
{
    kin_param_values p, before;
    kin_params_default(&p);
    before = p;
    char err[512] = "";
    if (kin_params_parse(text, "f.params", &p, err, sizeof err) != KIN_PARAMS_BAD)
        fail_msg("'%s' accepted", text);
    assert_contains(err, fragment1);
    if (fragment2)
        assert_contains(err, fragment2);
    assert_memory_equal(&p, &before, sizeof p);
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
    const kin_param_values p = parse_ok("eta_deg = 45\nalpha_min_deg = 10\nalpha_max_deg = 70\nL = 2\ns_max = 0.5\n");
    assert_close(p.v[TSE_PARAM_ETA], PI / 4, 1e-15);
    assert_close(p.v[TSE_PARAM_ALPHA_MIN], 10 * PI / 180, 1e-15);
    assert_close(p.v[TSE_PARAM_ALPHA_MAX], 70 * PI / 180, 1e-15);
    assert_true(p.v[TSE_PARAM_L] == 2.0); /* lengths are not converted */
    assert_true(p.v[TSE_PARAM_S_MAX] == 0.5);
    const kin_param_values n = parse_ok("eta_deg = -30\n");
    assert_close(n.v[TSE_PARAM_ETA], -PI / 6, 1e-15);
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
    const kin_param_values p = parse_ok(text);
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
    expect_error("L = 1.7\nbogus = 3\n", "f.params:2: unknown key 'bogus'", NULL);
    expect_error("eta = 30\n", "f.params:1: unknown key 'eta'", NULL); /* the file speaks degrees */
    expect_error("l = 1.7\n", "f.params:1: unknown key 'l'", NULL);    /* keys are case-sensitive */
    expect_error("alpha min_deg = 10\n", "f.params:1: unknown key", NULL);
    expect_error("= 3\n", "f.params:1: unknown key ''", NULL);
    expect_error("\n\nL 1.7\n", "f.params:3: expected 'key = value'", NULL);
    expect_error("k1 = 0.3\n# comment\nk1 = 0.4\n", "f.params:3: 'k1' given twice", "first on line 1");
    expect_error("eta_deg = 30\r\neta_deg = 30\r\n", "f.params:2: 'eta_deg' given twice", NULL);
}

static void test_value_errors_name_the_line(void **state)
{
    (void)state;
    static const char *const bad[] = {
        "k3 = 0.01x\n", "k3 =\n", "k3 = # nothing\n", "k3 = nan\n", "k3 = inf\n", "k3 = -inf\n",
        "k3 = 1e999\n", "k3 = 0,02\n", "k3 = 0.01 0.02\n", "k3 = 0.01 = 0.02\n", "k3 = x\n", "k3 = 1e\n",
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        char text[64];
        snprintf(text, sizeof text, "L = 1.727\n%s", bad[i]);
        expect_error(text, "f.params:2: value of k3 is not a finite number", NULL);
    }
    char longline[KIN_PARAMS_MAX_LINE + 16];
    memset(longline, ' ', sizeof longline);
    memcpy(longline, "L = 1.7", 7);
    strcpy(longline + sizeof longline - 3, "\n");
    char text[sizeof longline + 16];
    snprintf(text, sizeof text, "# one\n%s", longline);
    expect_error(text, "f.params:2: line longer than", NULL);
}

/* Every rule of kinematics.md, "Valid parameter sets": the error names the key and its line. */
static void test_invalid_sets_name_the_line(void **state)
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
        {"eta_deg = 90", "eta_deg"},
        {"eta_deg = -90", "eta_deg"},
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
        expect_error(text, want, "is invalid");
    }
    /* Valid at the edges the rules allow. */
    parse_ok("k1 = 1\nk3 = 0\ns_min = 0\nmu_min = 0\nnu_min = 0\n");
    /* The first key of the set that fails is named at the line that set it. */
    expect_error("s_max = 0.4\ns_min = 0.5\n", "f.params:1: s_max = 0.4 is invalid", NULL);
    expect_error("s_min = 0.5\ns_max = 0.4\n", "f.params:2: s_max = 0.4 is invalid", NULL);
    /* A key the file did not set is called the default value. */
    expect_error("alpha_min_deg = 80 # above the prototype's alpha_max (69.6 deg)\n",
                 "f.params: default value alpha_max_deg = ", "is invalid");
    expect_error("s_min = 1.2\n", "f.params: default value s_max = 0.9", "is invalid");
}

static void test_keys_follow_the_library_names(void **state)
{
    (void)state;
    for (int id = 1; id < TSE_PARAM_COUNT; ++id) {
        const char *lib = tse_param_name((tse_param_id)id), *key = kin_param_key((tse_param_id)id);
        const int angle = id == TSE_PARAM_ETA || id == TSE_PARAM_ALPHA_MIN || id == TSE_PARAM_ALPHA_MAX;
        char want[32];
        snprintf(want, sizeof want, "%s%s", lib, angle ? "_deg" : "");
        assert_string_equal(key, want);
    }
}

static void test_describe_invalid(void **state)
{
    (void)state;
    kin_param_values p = parse_ok("L = 1.7\neta_deg = 89.999999999\n");
    char err[512];
    kin_params_describe_invalid(&p, TSE_PARAM_ETA, "d.params", " in float precision", err, sizeof err);
    assert_contains(err, "d.params:2: eta_deg = 89.999999999 is invalid in float precision");
    kin_params_describe_invalid(&p, TSE_PARAM_K4, "d.params", "", err, sizeof err);
    assert_contains(err, "d.params: default value k4 = 0.11765 is invalid");
}

static void test_stream_and_file(void **state)
{
    (void)state;
    kin_param_values p;
    kin_params_default(&p);
    char err[512] = "";
    static char text[] = "k1 = 0.3\n";
    FILE *f = fmemopen(text, strlen(text), "r");
    assert_non_null(f);
    assert_int_equal(kin_params_parse_stream(f, "mem", &p, err, sizeof err), KIN_PARAMS_OK);
    fclose(f);
    assert_true(p.v[TSE_PARAM_K1] == 0.3);

    /* A NUL would hide the rest of the file from a string parser: refused. */
    static char nul[] = "k1 = 0.3\n\0k1 = 0.4\n";
    f = fmemopen(nul, sizeof nul - 1, "r");
    assert_non_null(f);
    assert_int_equal(kin_params_parse_stream(f, "mem", &p, err, sizeof err), KIN_PARAMS_BAD);
    assert_contains(err, "mem: contains a NUL byte");
    fclose(f);

    char *big = malloc(KIN_PARAMS_MAX_BYTES + 2);
    assert_non_null(big);
    memset(big, '\n', KIN_PARAMS_MAX_BYTES + 1);
    f = fmemopen(big, KIN_PARAMS_MAX_BYTES + 1, "r");
    assert_non_null(f);
    assert_int_equal(kin_params_parse_stream(f, "big", &p, err, sizeof err), KIN_PARAMS_BAD);
    assert_contains(err, "big: larger than");
    fclose(f);
    free(big);

    assert_int_equal(kin_params_load("/nonexistent/tse.params", &p, err, sizeof err), KIN_PARAMS_UNREADABLE);
    assert_contains(err, "/nonexistent/tse.params: cannot open");

    char path[] = "/tmp/tse_params_XXXXXX";
    const int fd = mkstemp(path);
    assert_true(fd >= 0);
    const char content[] = "L = 1.8\nbad line\n";
    assert_int_equal(write(fd, content, sizeof content - 1), (int)(sizeof content - 1));
    close(fd);
    kin_params_default(&p);
    assert_int_equal(kin_params_load(path, &p, err, sizeof err), KIN_PARAMS_BAD);
    char want[64];
    snprintf(want, sizeof want, "%s:2: expected 'key = value'", path);
    assert_contains(err, want);
    unlink(path);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_defaults_are_the_prototype),
        cmocka_unit_test(test_degrees_and_units),
        cmocka_unit_test(test_comments_blanks_crlf_and_lines),
        cmocka_unit_test(test_syntax_errors_name_the_line),
        cmocka_unit_test(test_value_errors_name_the_line),
        cmocka_unit_test(test_invalid_sets_name_the_line),
        cmocka_unit_test(test_keys_follow_the_library_names),
        cmocka_unit_test(test_describe_invalid),
        cmocka_unit_test(test_stream_and_file),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
