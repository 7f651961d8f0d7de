/* Exact number text for the DBC: products worked out by hand (the integer times the scale as
 * written in decimal), and a sweep that reads every printed range back. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "decimal_text.h"

static void expect_scaled(int64_t raw, double scale, const char *want)
{
    char buf[64];
    assert_int_equal(dec_scaled(raw, scale, buf, sizeof buf), 0);
    assert_string_equal(buf, want);
}

static void test_table_ranges(void **state)
{
    (void)state;
    /* The ranges the old DBC rounded: INT32 limits in nanometres, micro-units, the SAVE magic. */
    expect_scaled(2147483647, 1e-9, "2.147483647");
    expect_scaled(-2147483647 - 1, 1e-9, "-2.147483648");
    expect_scaled(2147483647, 1e-6, "2147.483647");
    expect_scaled(2147483647, 1e-3, "2147483.647");
    expect_scaled(1163280723, 1.0, "1163280723");
    expect_scaled(-2147483647 - 1, 1.0, "-2147483648");
    expect_scaled(-3141593, 1e-6, "-3.141593");
    expect_scaled(1000, 1e-6, "0.001");
    expect_scaled(60000000, 1e-6, "60");
    expect_scaled(65535, 1e-3, "65.535");
    expect_scaled(0, 1e-6, "0");
    expect_scaled(0, 1.0, "0");
}

/* The decimal the scale was written as, not the binary double's error: 3 x 0.1 is 0.3 although
 * 3.0 * 0.1 in double arithmetic is 0.30000000000000004. */
static void test_decimal_not_binary(void **state)
{
    (void)state;
    expect_scaled(3, 0.1, "0.3");
    expect_scaled(3, 1.0 / 3.0, "0.9999999999999999"); /* 3 x 0.3333333333333333 (16 digits) */
    expect_scaled(123456789, 1.5e-3, "185185.1835");     /* 123456789 x 1.5 = 185185183.5 */
    expect_scaled(7, 2.5e3, "17500");
    expect_scaled(1, 1e20, "100000000000000000000");
    expect_scaled(-1, 1e-20, "-0.00000000000000000001");
    expect_scaled(INT64_MIN, 1.0, "-9223372036854775808");
    expect_scaled(2, -0.5, "-1");
    expect_scaled(-2, -0.5, "1");
}

static void test_refusals(void **state)
{
    (void)state;
    char buf[64];
    assert_int_equal(dec_scaled(1, NAN, buf, sizeof buf), -1);
    assert_int_equal(dec_scaled(1, INFINITY, buf, sizeof buf), -1);
    assert_int_equal(dec_shortest(INFINITY, buf, sizeof buf), -1);
    /* "2.147483647" is 11 characters: 12 bytes hold it, 11 do not. */
    assert_int_equal(dec_scaled(2147483647, 1e-9, buf, 11), -1);
    assert_int_equal(dec_scaled(2147483647, 1e-9, buf, 12), 0);
    assert_string_equal(buf, "2.147483647");
    assert_int_equal(dec_scaled(1, 1e-300, buf, sizeof buf), -1);
    assert_int_equal(dec_shortest(1.0 / 3.0, buf, 5), -1);
}

static void test_shortest(void **state)
{
    (void)state;
    char buf[64];
    const struct {
        double x;
        const char *want;
    } cases[] = {{1e-6, "1e-06"}, {1e-9, "1e-09"}, {0.001, "0.001"}, {1.0, "1"}, {0.1, "0.1"},
                 {1.0 / 3.0, "0.3333333333333333"}, {1163280723.0, "1163280723"}, {-2.5, "-2.5"}};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        assert_int_equal(dec_shortest(cases[i].x, buf, sizeof buf), 0);
        assert_string_equal(buf, cases[i].want);
        assert_true(strtod(buf, NULL) == cases[i].x);
    }
}

/* Whatever the digits, the text read back and divided by the scale is the integer again, and a
 * nanometre scale never needs more than nine decimals. */
static void test_reads_back(void **state)
{
    (void)state;
    const double scales[] = {1e-9, 1e-6, 1e-3, 1.0};
    const int decimals[] = {9, 6, 3, 0};
    int64_t raw = -2147483648LL;
    for (int n = 0; n < 20000; ++n, raw += 214748 + n) {
        for (int s = 0; s < 4; ++s) {
            char buf[64];
            assert_int_equal(dec_scaled(raw, scales[s], buf, sizeof buf), 0);
            assert_true(llround(strtod(buf, NULL) / scales[s]) == raw);
            const char *point = strchr(buf, '.');
            assert_true(point == NULL || (int)strlen(point + 1) <= decimals[s]);
            assert_true(point == NULL || buf[strlen(buf) - 1] != '0');
        }
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_table_ranges), cmocka_unit_test(test_decimal_not_binary),
        cmocka_unit_test(test_refusals),     cmocka_unit_test(test_shortest),
        cmocka_unit_test(test_reads_back),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
