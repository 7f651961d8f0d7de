/* The host tools' rows and output numbers (host_tools/common/csv.h) and their line reader
 * (line_reader.h): what is a row of numbers, what is malformed, why and in which column, one NaN
 * spelling, headers, and lines returned exactly once whatever bytes they hold, a leading UTF-8 BOM
 * dropped. */
#define _POSIX_C_SOURCE 200809L /* fmemopen, open_memstream */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "csv.h"
#include "line_reader.h"

static int parse(const char *s, double *v, int max, const char **why)
{
    return csv_parse_row(s, strlen(s), v, max, why);
}

static void expect_malformed(const char *s, int max, const char *reason)
{
    double v[16];
    const char *why = "";
    const int n = parse(s, v, max, &why);
    if (n != -1)
        fail_msg("'%s' gave %d numbers, want malformed (%s)", s, n, reason);
    if (strcmp(why, reason))
        fail_msg("'%s': reason '%s', want '%s'", s, why, reason);
}

static void test_good_rows(void **state)
{
    (void)state;
    double v[12];
    const char *why = "";
    assert_int_equal(parse("0,0,1,0,0,0", v, 6, &why), 6);
    assert_true(v[2] == 1.0);
    assert_int_equal(parse("0.1,-0.05,1.1,0.1,-0.05,0.2\n", v, 6, &why), 6);
    assert_true(v[0] == 0.1 && v[1] == -0.05 && v[5] == 0.2); /* strtod rounds correctly */
    assert_int_equal(parse("1e-3, 2E+2 ,\t-3.5e0\t,4,5,6\r\n", v, 6, &why), 6);
    assert_true(v[0] == 1e-3 && v[1] == 200.0 && v[2] == -3.5);
    assert_int_equal(parse("1,2,3\r", v, 6, &why), 3); /* a CR alone ends the row too */
    assert_int_equal(parse("0x1p-2,+1,.5,5.,-0,7", v, 6, &why), 6);
    assert_true(v[0] == 0.25 && v[1] == 1.0 && v[2] == 0.5 && v[3] == 5.0 && v[4] == 0.0 && signbit(v[4]));
    /* Not finite, but numbers: the library decides what they mean. */
    assert_int_equal(parse("nan,inf,-inf,NaN,Infinity,1e999", v, 6, &why), 6);
    assert_true(isnan(v[0]) && v[1] == INFINITY && v[2] == -INFINITY && isnan(v[3]) && v[4] == INFINITY &&
                v[5] == INFINITY);
    /* Twelve numbers: fk's slides and seed. */
    assert_int_equal(parse("1,2,3,4,5,6,7,8,9,10,11,12", v, 12, &why), 12);
    assert_true(v[11] == 12.0);
    assert_int_equal(csv_parse_list("21,36,41", v, 3, &why), 3);
}

static void test_malformed_rows(void **state)
{
    (void)state;
    expect_malformed("", 6, "blank line");
    expect_malformed("\n", 6, "blank line");
    expect_malformed("\r\n", 6, "blank line");
    expect_malformed(" \t ", 6, "blank line");
    expect_malformed("1,,3", 6, "empty field");
    expect_malformed(",1,2", 6, "empty field");
    expect_malformed("1,2,", 6, "empty field");
    expect_malformed("1, ,2", 6, "empty field");
    expect_malformed("abc", 6, "not a number");
    expect_malformed("1,2,x", 6, "not a number");
    expect_malformed("1,\v2,3", 6, "not a number"); /* only spaces and tabs pad a field */
    expect_malformed("1,2,3 4", 6, "trailing text");
    expect_malformed("1,2,3x", 6, "trailing text");
    expect_malformed("1,2,1e", 6, "trailing text");
    expect_malformed("1,2\r,3", 6, "trailing text"); /* a CR inside the row is not a line end */
    expect_malformed("1;2;3", 6, "trailing text");
    expect_malformed("1,2,3,4,5,6,7", 6, "too many fields");
    char big[200];
    memset(big, '1', sizeof big - 1);
    big[sizeof big - 1] = '\0';
    expect_malformed(big, 6, "field too long");

    /* A NUL inside the row: the length says there is more than a C string would show. */
    double v[6];
    const char *why = "";
    assert_int_equal(csv_parse_row("0,0,1,0,0,0\0x", 13, v, 6, &why), -1);
    assert_string_equal(why, "NUL byte");
    assert_int_equal(csv_parse_row("0,0,1,0,0,0\0x", 11, v, 6, &why), 6);
}

/* The column at fault and its text, as a reader names them. */
static void expect_column(const char *s, int max, const char *reason, int column, const char *field)
{
    double v[16];
    csv_error e;
    if (csv_parse_fields(s, strlen(s), v, max, &e) != -1)
        fail_msg("'%s' accepted", s);
    assert_string_equal(e.why, reason);
    assert_int_equal(e.column, column);
    assert_int_equal(e.field.len, strlen(field));
    assert_memory_equal(e.field.text, field, strlen(field));
}

static void test_columns_at_fault(void **state)
{
    (void)state;
    expect_column("1,2,,3", 7, "empty field", 3, "");
    expect_column(" ,2", 7, "empty field", 1, "");
    expect_column("1,2,3,\t abc ,5", 7, "not a number", 4, "abc"); /* the padding is not the field's */
    expect_column("1,2x,3", 7, "trailing text", 2, "2x");
    expect_column("1,2,3,4", 3, "too many fields", 4, "4");
    expect_column("", 7, "blank line", 0, "");
    double v[4];
    csv_error e;
    assert_int_equal(csv_parse_fields("1,2\0,3", 6, v, 4, &e), -1);
    assert_string_equal(e.why, "NUL byte");
    assert_int_equal(e.column, 0);
}

static void test_split_and_header(void **state)
{
    (void)state;
    csv_span f[4];
    const char *row = " a ,\tb,,c d\r\n";
    assert_int_equal(csv_split(row, strlen(row), f, 4), 4);
    assert_int_equal(f[0].len, 1);
    assert_memory_equal(f[0].text, "a", 1);
    assert_int_equal(f[1].len, 1);
    assert_int_equal(f[2].len, 0);
    assert_int_equal(f[3].len, 3); /* the line end is not part of the last field */
    assert_memory_equal(f[3].text, "c d", 3);
    /* More fields than room: counted, not stored beyond max. */
    assert_int_equal(csv_split("1,2,3,4,5,6", 11, f, 2), 6);
    assert_int_equal(csv_split("", 0, f, 4), 1);

    static const char *const names[] = {"t", "x", "roll"};
    const char *yes[] = {"t,x,roll", " T , X ,Roll\r\n", "t,x,ROLL\n"};
    const char *no[] = {"t,x", "t,x,roll,", "t,x,rol", "t,x,roll,yaw", "t;x;roll", "x,t,roll", "t,x,r oll", ""};
    for (size_t i = 0; i < sizeof yes / sizeof yes[0]; ++i)
        if (!csv_is_header(yes[i], strlen(yes[i]), names, 3))
            fail_msg("'%s' is the header", yes[i]);
    for (size_t i = 0; i < sizeof no / sizeof no[0]; ++i)
        if (csv_is_header(no[i], strlen(no[i]), names, 3))
            fail_msg("'%s' is not the header", no[i]);
}

static char *capture(void (*put)(FILE *, const double *, int), const double *v, int n)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    assert_non_null(f);
    put(f, v, n);
    fclose(f);
    return buf;
}

static void put_nans(FILE *f, const double *v, int n)
{
    (void)v;
    csv_put_nans(f, n);
}

static void test_output_numbers(void **state)
{
    (void)state;
    const double v[6] = {NAN, -NAN, 0.1, -0.0, INFINITY, 0.43015083911167};
    char *s = capture(csv_put_numbers, v, 6);
    assert_string_equal(s, ",nan,nan,0.10000000000000001,-0,inf,0.43015083911167001");
    free(s);
    s = capture(put_nans, NULL, 3);
    assert_string_equal(s, ",nan,nan,nan");
    free(s);
    /* %.17g reads back to the same double. */
    double back;
    const char *why;
    assert_int_equal(csv_parse_list("0.43015083911167001", &back, 1, &why), 1);
    assert_true(back == 0.43015083911167);
}

static void test_line_reader(void **state)
{
    (void)state;
    static char data[] = "a\r\nb\0c\n\nlast";
    FILE *f = fmemopen(data, sizeof data - 1, "r");
    assert_non_null(f);
    line_reader r;
    line_reader_init(&r, f);
    const char *line;
    size_t len;
    int overlong;
    assert_int_equal(line_reader_next(&r, &line, &len, &overlong), 1);
    assert_int_equal(len, 2); /* the CR is kept: the row parser decides about it */
    assert_memory_equal(line, "a\r", 2);
    assert_int_equal(line_reader_next(&r, &line, &len, &overlong), 1);
    assert_int_equal(len, 3); /* one line with a NUL in it, not two */
    assert_memory_equal(line, "b\0c", 3);
    assert_int_equal(line_reader_next(&r, &line, &len, &overlong), 1);
    assert_int_equal(len, 0);
    assert_int_equal(line_reader_next(&r, &line, &len, &overlong), 1);
    assert_string_equal(line, "last"); /* no newline at the end: still a line */
    assert_int_equal(overlong, 0);
    assert_int_equal(line_reader_next(&r, &line, &len, &overlong), 0);
    fclose(f);
}

static void test_line_reader_overlong(void **state)
{
    (void)state;
    const size_t n = 3 * LINE_READER_MAX;
    char *data = malloc(n + 8);
    assert_non_null(data);
    memset(data, 'x', n);
    memcpy(data + n, "\ny\n", 3);
    FILE *f = fmemopen(data, n + 3, "r");
    assert_non_null(f);
    line_reader r;
    line_reader_init(&r, f);
    const char *line;
    size_t len;
    int overlong;
    assert_int_equal(line_reader_next(&r, &line, &len, &overlong), 1);
    assert_int_equal(overlong, 1);
    assert_int_equal(len, LINE_READER_MAX);
    /* The rest of the long line is consumed: the next line is the next line. */
    assert_int_equal(line_reader_next(&r, &line, &len, &overlong), 1);
    assert_int_equal(overlong, 0);
    assert_string_equal(line, "y");
    assert_int_equal(line_reader_next(&r, &line, &len, &overlong), 0);
    fclose(f);
    free(data);

    /* Exactly the limit is not too long. */
    char *edge = malloc(LINE_READER_MAX + 2);
    assert_non_null(edge);
    memset(edge, '7', LINE_READER_MAX);
    edge[LINE_READER_MAX] = '\n';
    f = fmemopen(edge, LINE_READER_MAX + 1, "r");
    assert_non_null(f);
    line_reader_init(&r, f);
    assert_int_equal(line_reader_next(&r, &line, &len, &overlong), 1);
    assert_int_equal(overlong, 0);
    assert_int_equal(len, LINE_READER_MAX);
    assert_int_equal(line_reader_next(&r, &line, &len, &overlong), 0);
    fclose(f);
    free(edge);
}

/* One line of the stream, from the start. */
static void next_is(line_reader *r, const char *want, size_t want_len)
{
    const char *line;
    size_t len;
    int overlong;
    assert_int_equal(line_reader_next(r, &line, &len, &overlong), 1);
    assert_int_equal(overlong, 0);
    assert_int_equal(len, want_len);
    assert_memory_equal(line, want, want_len);
}

static void test_line_reader_bom(void **state)
{
    (void)state;
    line_reader r;
    const char *line;
    size_t len;
    int overlong;
    /* Dropped at the very start only; a second one, or one on a later line, is data. */
    static char data[] = "\xEF\xBB\xBF" "1,2\n\xEF\xBB\xBF" "3\n";
    FILE *f = fmemopen(data, sizeof data - 1, "r");
    assert_non_null(f);
    line_reader_init(&r, f);
    next_is(&r, "1,2", 3);
    next_is(&r, "\xEF\xBB\xBF" "3", 4);
    assert_int_equal(line_reader_next(&r, &line, &len, &overlong), 0);
    fclose(f);

    static char twice[] = "\xEF\xBB\xBF\xEF\xBB\xBF" "x\n";
    f = fmemopen(twice, sizeof twice - 1, "r");
    assert_non_null(f);
    line_reader_init(&r, f);
    next_is(&r, "\xEF\xBB\xBF" "x", 4);
    fclose(f);

    /* Part of a BOM is not one, and a short first line is not mistaken for one. */
    static char part[] = "\xEF\xBB" "x\nab\n";
    f = fmemopen(part, sizeof part - 1, "r");
    assert_non_null(f);
    line_reader_init(&r, f);
    next_is(&r, "\xEF\xBB" "x", 3);
    next_is(&r, "ab", 2);
    fclose(f);

    /* Nothing but a BOM is an empty stream; a BOM and a newline is one empty line. */
    static char only[] = "\xEF\xBB\xBF";
    f = fmemopen(only, sizeof only - 1, "r");
    assert_non_null(f);
    line_reader_init(&r, f);
    assert_int_equal(line_reader_next(&r, &line, &len, &overlong), 0);
    fclose(f);
    static char empty_line[] = "\xEF\xBB\xBF\n";
    f = fmemopen(empty_line, sizeof empty_line - 1, "r");
    assert_non_null(f);
    line_reader_init(&r, f);
    next_is(&r, "", 0);
    assert_int_equal(line_reader_next(&r, &line, &len, &overlong), 0);
    fclose(f);

    /* The BOM counts against no line's length: a BOM and LINE_READER_MAX bytes is not too long. */
    char *edge = malloc(LINE_READER_MAX + 8);
    assert_non_null(edge);
    memcpy(edge, "\xEF\xBB\xBF", 3);
    memset(edge + 3, '7', LINE_READER_MAX);
    edge[3 + LINE_READER_MAX] = '\n';
    f = fmemopen(edge, LINE_READER_MAX + 4, "r");
    assert_non_null(f);
    line_reader_init(&r, f);
    assert_int_equal(line_reader_next(&r, &line, &len, &overlong), 1);
    assert_int_equal(overlong, 0);
    assert_int_equal(len, LINE_READER_MAX);
    assert_true(line[0] == '7');
    fclose(f);
    free(edge);

    assert_int_equal(utf8_bom_length("\xEF\xBB\xBFk", 4), 3);
    assert_int_equal(utf8_bom_length("\xEF\xBB\xBF", 2), 0);
    assert_int_equal(utf8_bom_length("k = 1", 5), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_good_rows),
        cmocka_unit_test(test_malformed_rows),
        cmocka_unit_test(test_output_numbers),
        cmocka_unit_test(test_line_reader),
        cmocka_unit_test(test_line_reader_overlong),
        cmocka_unit_test(test_line_reader_bom),
        cmocka_unit_test(test_columns_at_fault),
        cmocka_unit_test(test_split_and_header),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
