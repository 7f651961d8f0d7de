/* tse-kin's command-line options (options.h): defaults, both spellings, and a refusal naming the
 * option for everything a command does not take or a value it cannot use. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "options.h"

static const unsigned ALL = KIN_OPT_PARAMS | KIN_OPT_PRECISION | KIN_OPT_GRID | KIN_OPT_ORIENTATION | KIN_OPT_Z |
                            KIN_OPT_N;

/* Splits a space-separated command line (no quoting needed here). */
static int run(const char *line, unsigned allowed, kin_options *o, char *err, size_t errlen)
{
    static char buf[512];
    char *args[32];
    int n = 0;
    strcpy(buf, line);
    for (char *t = strtok(buf, " "); t && n < 32; t = strtok(NULL, " "))
        args[n++] = t;
    kin_options_default(o);
    return kin_options_parse(n, args, allowed, o, err, errlen);
}

static void expect_ok(const char *line, unsigned allowed, kin_options *o)
{
    char err[512] = "";
    if (run(line, allowed, o, err, sizeof err) != 0)
        fail_msg("'%s' refused: %s", line, err);
}

static void expect_refused(const char *line, unsigned allowed, const char *fragment)
{
    kin_options o;
    char err[512] = "";
    if (run(line, allowed, &o, err, sizeof err) == 0)
        fail_msg("'%s' accepted", line);
    if (!strstr(err, fragment))
        fail_msg("'%s': message '%s' does not contain '%s'", line, err, fragment);
}

static void test_defaults(void **state)
{
    (void)state;
    kin_options o;
    expect_ok("", ALL, &o);
    assert_null(o.params_path);
    assert_int_equal(o.use_float, 0);
    assert_int_equal(o.grid[0], 21);
    assert_int_equal(o.grid[1], 36);
    assert_int_equal(o.grid[2], 41);
    assert_true(o.orientation[0] == 0 && o.orientation[1] == 0 && o.orientation[2] == 0);
    assert_int_equal(o.n_z, 0);
    assert_int_equal(o.bench_n, 2000);
}

static void test_values(void **state)
{
    (void)state;
    kin_options o;
    expect_ok("--params a.params --precision float", ALL, &o);
    assert_string_equal(o.params_path, "a.params");
    assert_int_equal(o.use_float, 1);
    expect_ok("--params=b.params --precision=double", ALL, &o);
    assert_string_equal(o.params_path, "b.params");
    assert_int_equal(o.use_float, 0);
    expect_ok("--precision float --precision double", ALL, &o); /* the last one counts */
    assert_int_equal(o.use_float, 0);
    expect_ok("--grid 2,1,2", ALL, &o);
    assert_true(o.grid[0] == 2 && o.grid[1] == 1 && o.grid[2] == 2);
    expect_ok("--grid=100,200,300", ALL, &o);
    assert_true(o.grid[0] == 100 && o.grid[1] == 200 && o.grid[2] == 300);
    expect_ok("--orientation 0.1,-0.2,0.3", ALL, &o);
    assert_true(o.orientation[0] == 0.1 && o.orientation[1] == -0.2 && o.orientation[2] == 0.3);
    expect_ok("--z 0.5,1,1.5", ALL, &o);
    assert_int_equal(o.n_z, 3);
    assert_true(o.z[0] == 0.5 && o.z[1] == 1.0 && o.z[2] == 1.5);
    expect_ok("--n 2", ALL, &o);
    assert_int_equal(o.bench_n, 2);
    expect_ok("--n 10000000", ALL, &o);
    assert_int_equal(o.bench_n, 10000000);
}

static void test_refusals(void **state)
{
    (void)state;
    expect_refused("--bogus", ALL, "'--bogus'");
    expect_refused("stray", ALL, "'stray'");
    expect_refused("-p x", ALL, "'-p'");
    expect_refused("--params", ALL, "--params needs a value");
    expect_refused("--params=", ALL, "--params");
    expect_refused("--precision quad", ALL, "'quad'");
    expect_refused("--precision Float", ALL, "'Float'");
    expect_refused("--grid 2,1,2", KIN_OPT_PARAMS | KIN_OPT_PRECISION, "does not take --grid");
    expect_refused("--n 5", KIN_OPT_PARAMS, "does not take --n");
    expect_refused("--precision float", KIN_OPT_PARAMS | KIN_OPT_N, "does not take --precision");
    static const char *const grids[] = {
        "1,2,3",   "2,0,2",   "2,1,1",         "2,1",      "2,1,2,3",   "2.0,1,2",  "2e1,1,2",      " 2,1,2",
        "+2,1,2",  "-2,1,2",  "a,b,c",         "2,,2",     "100001,1,2", "2,1,2x",  "10000,10000,10", "",
    };
    for (size_t i = 0; i < sizeof grids / sizeof grids[0]; ++i) {
        char line[64];
        snprintf(line, sizeof line, "--grid=%s", grids[i]);
        expect_refused(line, ALL, "--grid takes NR,NPHI,NZ");
    }
    expect_refused("--orientation 0,0", ALL, "--orientation takes three finite angles");
    expect_refused("--orientation nan,0,0", ALL, "--orientation takes three finite angles");
    expect_refused("--orientation 0,0,0,0", ALL, "--orientation takes three finite angles");
    expect_refused("--z abc", ALL, "--z takes");
    expect_refused("--z 1,,2", ALL, "--z takes");
    expect_refused("--z inf", ALL, "--z takes");
    expect_refused("--n 1", ALL, "--n takes a whole number");
    expect_refused("--n 1e3", ALL, "--n takes a whole number");
    expect_refused("--n 10000001", ALL, "--n takes a whole number");
    expect_refused("--n -5", ALL, "--n takes a whole number");
}

/* The design study's options: the --points switch, --jobs, positional arguments (sweep's
 * PARAM FROM TO N, negative numbers included), and the flags that tell a command's own defaults
 * from values given. */
static void test_study_options(void **state)
{
    (void)state;
    const unsigned sweep = KIN_OPT_ARGS | KIN_OPT_PARAMS | KIN_OPT_GRID | KIN_OPT_JOBS;
    kin_options o;
    expect_ok("eta_deg -60 60 --jobs 3 25", sweep, &o);
    assert_int_equal(o.n_args, 4);
    assert_string_equal(o.args[0], "eta_deg");
    assert_string_equal(o.args[1], "-60");
    assert_string_equal(o.args[2], "60");
    assert_string_equal(o.args[3], "25");
    assert_int_equal(o.jobs, 3);
    assert_int_equal(o.grid_set, 0);
    expect_ok("k1 0 1 5 --grid=4,6,5 --jobs=1", sweep, &o);
    assert_int_equal(o.grid_set, 1);
    assert_int_equal(o.grid[0], 4);
    assert_int_equal(o.jobs, 1);
    expect_ok("", sweep, &o);
    assert_int_equal(o.n_args, 0);
    assert_int_equal(o.jobs, 0);
    expect_refused("a b c d e", sweep, "'e'");
    expect_refused("k1 0 1 5 --jobs 0", sweep, "--jobs");
    expect_refused("k1 0 1 5 --jobs 257", sweep, "--jobs");
    expect_refused("k1 0 1 5 --jobs", sweep, "--jobs needs a value");
    expect_refused("k1", ALL, "unexpected argument 'k1'");
    expect_ok("--points --grid 3,3,3", KIN_OPT_POINTS | KIN_OPT_GRID, &o);
    assert_int_equal(o.points, 1);
    expect_ok("--grid 3,3,3", KIN_OPT_POINTS | KIN_OPT_GRID, &o);
    assert_int_equal(o.points, 0);
    expect_refused("--points=1", KIN_OPT_POINTS, "--points takes no value");
    expect_refused("--points", ALL, "does not take --points");
    expect_ok("--n 7", KIN_OPT_N, &o);
    assert_int_equal(o.n_set, 1);
    assert_int_equal(o.bench_n, 7);
    expect_ok("", KIN_OPT_N, &o);
    assert_int_equal(o.n_set, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_defaults),
        cmocka_unit_test(test_values),
        cmocka_unit_test(test_refusals),
        cmocka_unit_test(test_study_options),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
