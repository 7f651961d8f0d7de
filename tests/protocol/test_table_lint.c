/* The table checks protogen runs before printing: a clean table passes, and each defect a
 * document could not carry is reported once, naming the message and field. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "table_lint.h"

static char report[4096];

/* Runs the lint on one message and keeps what it wrote. */
static int lint_one(const proto_def *d)
{
    FILE *err = tmpfile();
    assert_non_null(err);
    const int n = table_lint(d, 1, err);
    rewind(err);
    const size_t len = fread(report, 1, sizeof report - 1, err);
    report[len] = '\0';
    fclose(err);
    return n;
}

/* 6 bytes: a sequence number and a 32-bit length in micrometres at byte 2. */
static proto_def good(void)
{
    const proto_def d = {PM_MOVE_COMMIT, 0x0D, "MSG", PROTO_TO_CONTROLLER, 6, 2,
                         {{"seq", PF_U8, 0, 0, 255, "", 1.0, 0, "sequence"},
                          {"len", PF_I32, 2, INT32_MIN, INT32_MAX, "m", 1e-6, 0, "a length"}},
                         "a message"};
    return d;
}

static void expect_one(const proto_def *d, const char *names, const char *words)
{
    assert_int_equal(lint_one(d), 1);
    assert_non_null(strstr(report, names));
    assert_non_null(strstr(report, words));
    assert_non_null(strstr(report, "firmware/include/fw/proto_messages.def"));
}

static void test_clean(void **state)
{
    (void)state;
    proto_def d = good();
    assert_int_equal(lint_one(&d), 0);
    assert_string_equal(report, "");
    assert_int_equal(table_lint(proto_table, PM_COUNT, stderr), 0); /* the real table prints */
}

static void test_scaled_without_unit(void **state)
{
    (void)state;
    proto_def d = good();
    d.fields[1].unit = "";
    expect_one(&d, "MSG.len", "no unit");
}

static void test_text_unfit_for_dbc(void **state)
{
    (void)state;
    proto_def d = good();
    d.fields[0].doc = "\"SAVE\"";
    expect_one(&d, "MSG.seq", "doc");
    d = good();
    d.fields[0].doc = "";
    expect_one(&d, "MSG.seq", "doc is missing");
    d = good();
    d.doc = "a | b";
    expect_one(&d, "MSG", "doc");
    d = good();
    d.fields[1].unit = "\xb5m"; /* micro sign in Latin-1 */
    expect_one(&d, "MSG.len", "unit");
    d = good();
    d.fields[1].name = "my len";
    expect_one(&d, "'my len'", "identifier");
}

static void test_ranges_and_layout(void **state)
{
    (void)state;
    proto_def d = good();
    d.fields[0].max = 256; /* past u8 */
    expect_one(&d, "MSG.seq", "outside its type's 0..255");
    d = good();
    d.fields[0].min = 5;
    d.fields[0].max = 4;
    expect_one(&d, "MSG.seq", "empty");
    d = good();
    d.fields[1].scale = 0.0;
    expect_one(&d, "MSG.len", "not a positive number");
    d = good();
    d.fields[1].offset = 3; /* bytes 3..6 of a 6-byte message */
    expect_one(&d, "MSG.len", "past the message's 6");
    d = good();
    d.fields[1].offset = 0; /* on top of seq */
    expect_one(&d, "MSG.len", "inside or before the previous field");
}

/* The code tables (a timing refusal's limit, a refused set's rule): the real ones print; values
 * out of order, a name that is no identifier, missing or unprintable words are each reported. */
static int lint_codes(const proto_code *c)
{
    FILE *err = tmpfile();
    assert_non_null(err);
    const int n = codes_lint(c, "CODES", err);
    rewind(err);
    const size_t len = fread(report, 1, sizeof report - 1, err);
    report[len] = '\0';
    fclose(err);
    return n;
}

static void test_codes(void **state)
{
    (void)state;
    assert_int_equal(lint_codes(proto_slide_limits), 0);
    assert_int_equal(lint_codes(proto_param_rules), 0);
    const proto_code skip[] = {{0, "a", "words"}, {2, "b", "words"}, {0, 0, 0}};
    assert_int_equal(lint_codes(skip), 1);
    assert_non_null(strstr(report, "CODES: code 'b' has value 2 where 1 is due"));
    const proto_code name[] = {{0, "a b", "words"}, {0, 0, 0}};
    assert_int_equal(lint_codes(name), 1);
    assert_non_null(strstr(report, "is not an identifier"));
    const proto_code words[] = {{0, "a", ""}, {1, "b", "x | y"}, {2, "c", 0}, {0, 0, 0}};
    assert_int_equal(lint_codes(words), 3);
    assert_non_null(strstr(report, "code 'b': words are missing or hold"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_clean),
        cmocka_unit_test(test_codes),
        cmocka_unit_test(test_scaled_without_unit),
        cmocka_unit_test(test_text_unfit_for_dbc),
        cmocka_unit_test(test_ranges_and_layout),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
