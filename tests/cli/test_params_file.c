/* tse-kin's parameter file and row parser. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "csv.h"
#include "params_file.h"

static void expect_error(const char *text, const char *fragment)
{
    kin_param_values p, before;
    kin_params_default(&p);
    before = p;
    char err[256] = "";
    assert_int_equal(kin_params_parse(text, "f.params", &p, err, sizeof err), -1);
    if (!strstr(err, fragment))
        fail_msg("error '%s' does not contain '%s'", err, fragment);
    assert_memory_equal(&p, &before, sizeof p); /* nothing half-applied */
}

static void test_defaults_and_degrees(void **state)
{
    (void)state;
    kin_param_values p;
    kin_params_default(&p);
    char err[256];
    const char *text = "# a design\n\nL = 2.0   # metres\neta_deg = 45\r\n  alpha_max_deg=70\n";
    assert_int_equal(kin_params_parse(text, "f", &p, err, sizeof err), 0);
    assert_true(p.v[TSE_PARAM_L] == 2.0);
    assert_true(fabs(p.v[TSE_PARAM_ETA] - M_PI / 4) < 1e-15);
    assert_true(fabs(p.v[TSE_PARAM_ALPHA_MAX] - 70 * M_PI / 180) < 1e-15);
    assert_true(p.v[TSE_PARAM_K1] == 0.2647); /* untouched keys keep the prototype's */
    assert_int_equal(p.line[TSE_PARAM_ETA], 4);
    assert_int_equal(p.line[TSE_PARAM_K1], 0);
}

static void test_errors_name_the_line(void **state)
{
    (void)state;
    expect_error("L = 1.7\nbogus = 3\n", "f.params:2: unknown key 'bogus'");
    expect_error("k1 = 0.3\nk1 = 0.4\n", "f.params:2: 'k1' given twice (first on line 1)");
    expect_error("\n\nk3 = 0.01x\n", "f.params:3: '0.01x' is not a finite number for k3");
    expect_error("k3 =\n", "f.params:1: '' is not a finite number");
    expect_error("k4 = nan\n", "f.params:1: 'nan' is not a finite number for k4");
    expect_error("L 1.7\n", "f.params:1: expected 'key = value'");
    expect_error("s_min = 0.5\ns_max = 0.4\n", "f.params:2: invalid value of s_max");
    expect_error("k1 = 1.5\n", "f.params:1: invalid value of k1");
    expect_error("alpha_min_deg = 80\n", "the default value of alpha_max_deg is invalid");
}

static void test_rows(void **state)
{
    (void)state;
    double v[12];
    const char *why = "";
    assert_int_equal(csv_parse_row("1,2.5,-3e-2,4,5,6\n", v, 6, &why), 6);
    assert_true(v[2] == -3e-2);
    assert_int_equal(csv_parse_row("1, 2 ,3,4,5,6\r\n", v, 6, &why), 6);
    assert_int_equal(csv_parse_row("nan,inf,0,0,0,0", v, 6, &why), 6);
    assert_true(isnan(v[0]) && isinf(v[1]));
    assert_int_equal(csv_parse_row("1,2,3", v, 6, &why), 3);
    assert_int_equal(csv_parse_row("1,,3", v, 6, &why), -1);
    assert_string_equal(why, "empty field");
    assert_int_equal(csv_parse_row("1,2,x", v, 6, &why), -1);
    assert_string_equal(why, "not a number");
    assert_int_equal(csv_parse_row("1,2,3 4", v, 6, &why), -1);
    assert_string_equal(why, "trailing text");
    assert_int_equal(csv_parse_row("1,2,3,4,5,6,7", v, 6, &why), -1);
    assert_string_equal(why, "too many fields");
    assert_int_equal(csv_parse_row("", v, 6, &why), -1);
    assert_int_equal(csv_parse_row("1,2,", v, 6, &why), -1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_defaults_and_degrees),
        cmocka_unit_test(test_errors_name_the_line),
        cmocka_unit_test(test_rows),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
