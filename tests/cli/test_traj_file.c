/* The trajectory file reader (host_tools/common/traj_file.h): every rule of its header, accepted
 * and refused, with the line the message names.  Expected values are the rules' own figures (the
 * wire's +-4 m, +-3.141593 rad, 1 ms to 60 s in whole microseconds) and hand arithmetic on them. */
#define _POSIX_C_SOURCE 200809L /* mkstemp, mkdtemp */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "traj_file.h"

static char path[64];

/* Writes len bytes to a fresh file whose name is in `path`. */
static void write_file(const char *data, size_t len)
{
    strcpy(path, "/tmp/tse_traj_XXXXXX");
    const int fd = mkstemp(path);
    assert_true(fd >= 0);
    assert_int_equal(write(fd, data, len), (ssize_t)len);
    close(fd);
}

static int read_text(const char *text, traj_row **rows, char *err, size_t errlen)
{
    write_file(text, strlen(text));
    const int n = traj_file_read(path, rows, err, errlen);
    unlink(path);
    return n;
}

/* The text is accepted with n rows; the rows are returned (caller frees). */
static traj_row *accept(const char *text, int n)
{
    traj_row *rows = NULL;
    char err[512] = "";
    const int got = read_text(text, &rows, err, sizeof err);
    if (got != n)
        fail_msg("%d rows, want %d (%s) for:\n%s", got, n, err, text);
    assert_non_null(rows);
    return rows;
}

/* The text is refused with a message "PATH:" followed by want (want starts with the line, "3: ...",
 * or is ": ..." for a message about the whole file), and nothing is returned. */
static void refuse(const char *text, const char *want)
{
    traj_row *rows = (traj_row *)&rows; /* not NULL: the reader must clear it */
    char err[512] = "";
    const int got = read_text(text, &rows, err, sizeof err);
    if (got != -1)
        fail_msg("accepted (%d rows), want '%s', for:\n%s", got, want, text);
    assert_null(rows);
    char full[600];
    snprintf(full, sizeof full, "%s%s%s", path, want[0] == ':' ? "" : ":", want);
    if (strncmp(err, full, strlen(full)))
        fail_msg("message '%s', want it to start with '%s'", err, full);
}

static void test_rows_values_and_lines(void **state)
{
    (void)state;
    traj_row *r = accept("# a path\n"
                         "\n"
                         "0.5, 0.1,-0.05,1.1, 0.1,-0.05,0.2\n"
                         "  # indented comment\n"
                         "\t \n"
                         "1.5,0,0,1,0,0,0",
                         2);
    assert_true(r[0].t == 0.5);
    assert_true(r[0].p[0] == 0.1 && r[0].p[1] == -0.05 && r[0].p[2] == 1.1);
    assert_true(r[0].p[3] == 0.1 && r[0].p[4] == -0.05 && r[0].p[5] == 0.2);
    assert_int_equal(r[0].line, 3);
    assert_true(r[1].t == 1.5 && r[1].p[2] == 1.0);
    assert_int_equal(r[1].line, 6); /* the last line has no newline: still a row */
    free(r);
}

static void test_crlf_bom_and_header(void **state)
{
    (void)state;
    /* A BOM, a comment, a header in mixed case with spaces, CRLF throughout. */
    traj_row *r = accept("\xEF\xBB\xBF# exported\r\n"
                         " T , X,y,Z ,ROLL,pitch, Yaw\r\n"
                         "0.001,0,0,1,0,0,0\r\n"
                         "\r\n"
                         "0.002,0,0,1.001,0,0,0\r\n",
                         2);
    assert_int_equal(r[0].line, 3);
    assert_int_equal(r[1].line, 5);
    assert_true(r[1].p[2] == 1.001);
    free(r);
    /* A BOM directly before the first row. */
    r = accept("\xEF\xBB\xBF" "0.25,1,2,3,0.5,0.25,0.125\n", 1);
    assert_true(r[0].t == 0.25 && r[0].p[0] == 1.0 && r[0].p[5] == 0.125);
    assert_int_equal(r[0].line, 1);
    free(r);
    /* The header is optional, and only the first line other than blanks and comments may be one. */
    refuse("0.1,0,0,1,0,0,0\nt,x,y,z,roll,pitch,yaw\n", "2: column 1 (t): not a number 't'");
    /* Only at the very start is a BOM skipped. */
    refuse("0.1,0,0,1,0,0,0\n\xEF\xBB\xBF" "0.2,0,0,1,0,0,0\n", "2: column 1 (t): not a number");
}

static void test_first_line_neither_header_nor_row(void **state)
{
    (void)state;
    refuse("# c\ntime,x,y,z,roll,pitch,yaw\n0.1,0,0,1,0,0,0\n",
           "2: neither the header t,x,y,z,roll,pitch,yaw nor a row of 7 numbers: 'time,x,y,z,roll,pitch,yaw'");
    refuse("t,x,y,z,roll,pitch,yaw,extra\n", "1: neither the header");
    refuse("t,x,y,z,roll,pitch\n", "1: neither the header");
    refuse("t;x;y;z;roll;pitch;yaw\n", "1: neither the header");
    /* A first line that starts with a number is judged as a row. */
    refuse("0.1,0,abc,1,0,0,0\n", "1: column 3 (y): not a number 'abc'");
}

static void test_shifted_and_malformed_columns(void **state)
{
    (void)state;
    const char *ok = "0.1,0,0,1,0,0,0\n0.2,0,0,1,0,0,0\n";
    static const struct {
        const char *row;
        const char *want;
    } cases[] = {
        {"1,2,,3,4,5,6", "3: column 3 (y): empty"},
        {",1,2,3,0,0,0", "3: column 1 (t): empty"},
        {"1,0,0,1,0,0,", "3: column 7 (yaw): empty"},
        {"1,0, ,1,0,0,0", "3: column 3 (y): empty"},
        {"1,2,3,4,5,6,7,8", "3: 8 columns, expected 7 (t,x,y,z,roll,pitch,yaw)"},
        {"1,0,0,1,0,0,0,", "3: 8 columns, expected 7 (t,x,y,z,roll,pitch,yaw)"},
        {"1,0,0,1,0,0", "3: 6 columns, expected 7 (t,x,y,z,roll,pitch,yaw)"},
        {"1;0;0;1;0;0;0", "3: 1 column, expected 7"},
        {"1,0,abc,1,0,0,0", "3: column 3 (y): not a number 'abc'"},
        {"1,0,0,1x,0,0,0", "3: column 4 (z): not a number '1x'"},
        {"1,0,0,1 2,0,0,0", "3: column 4 (z): not a number '1 2'"},
        {"1,0,0,1,0,0,0 x", "3: column 7 (yaw): not a number '0 x'"},
        {"1,0,0,1,0,0\r,0", "3: column 6 (pitch): not a number '0?'"},
        {"1,0,0,1,nan,0,0", "3: column 5 (roll): not a finite number 'nan'"},
        {"inf,0,0,1,0,0,0", "3: column 1 (t): not a finite number 'inf'"},
        {"1,-1e999,0,1,0,0,0", "3: column 2 (x): not a finite number '-1e999'"},
        {"1,0,0,1,0,0,0,1,2,3", "3: 10 columns, expected 7"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        char text[256];
        snprintf(text, sizeof text, "%.32s%s\n", ok, cases[i].row);
        refuse(text, cases[i].want);
    }
    /* A line holding a NUL byte. */
    static const char nul[] = "0.1,0,0,1,0,0,0\n0.2,0,0,1\0,0,0,0\n";
    write_file(nul, sizeof nul - 1);
    traj_row *rows;
    char err[256];
    assert_int_equal(traj_file_read(path, &rows, err, sizeof err), -1);
    char want[128];
    snprintf(want, sizeof want, "%s:2: NUL byte", path);
    assert_memory_equal(err, want, strlen(want));
    unlink(path);
}

static void test_wire_range(void **state)
{
    (void)state;
    /* Exactly at the edges: accepted. */
    traj_row *r = accept("1,4,-4,4,3.141593,-3.141593,3.141593\n"
                         "2,-4,4,-4,-3.141593,3.141593,-3.141593\n"
                         "3,0,0,1,3.14159265358979,-3.14159265358979,0\n", /* pi is inside */
                         3);
    assert_true(r[0].p[0] == 4.0 && r[1].p[0] == -4.0 && r[0].p[3] == 3.141593);
    free(r);
    /* Just outside: refused, naming the column, the value as written, the unit and the range. */
    refuse("1,4.000001,0,1,0,0,0\n", "1: column 2 (x) = 4.000001 m is outside the wire's range -4..4 m");
    refuse("1,0,-4.0000001,1,0,0,0\n", "1: column 3 (y) = -4.0000001 m is outside the wire's range -4..4 m");
    refuse("# c\n1,0,0,4.5,0,0,0\n", "2: column 4 (z) = 4.5 m is outside the wire's range -4..4 m");
    refuse("1,0,0,1,3.1415931,0,0\n",
           "1: column 5 (roll) = 3.1415931 rad is outside the wire's range -3.141593..3.141593 rad");
    refuse("1,0,0,1,0,-3.141594,0\n", "1: column 6 (pitch) = -3.141594 rad is outside the wire's range");
    refuse("1,0,0,1,0,0,6.3\n", "1: column 7 (yaw) = 6.3 rad is outside the wire's range");
}

static void test_time_rules(void **state)
{
    (void)state;
    /* The first row: 0.001 s to 60 s from the moment the controller takes it. */
    free(accept("0.001,0,0,1,0,0,0\n", 1));
    free(accept("60,0,0,1,0,0,0\n", 1));
    refuse("0,0,0,1,0,0,0\n", "1: t = 0 s: the first row's t must be 0.001 s to 60 s");
    refuse("-1,0,0,1,0,0,0\n", "1: t = -1 s: the first row's t must be 0.001 s to 60 s");
    refuse("0.0009,0,0,1,0,0,0\n", "1: t = 0.0009 s: the first row's t must be");
    refuse("60.000001,0,0,1,0,0,0\n", "1: t = 60.000001 s: the first row's t must be");
    refuse("1e300,0,0,1,0,0,0\n", "1: t = 1e+300 s: the first row's t must be");
    /* Rounded to whole microseconds: 0.0009996 s is 1000 us, 0.0009994 s is 999 us. */
    free(accept("0.0009996,0,0,1,0,0,0\n", 1));
    refuse("0.0009994,0,0,1,0,0,0\n", "1: t = 0.0009994 s: the first row's t must be");

    /* Later rows: 0.001 s to 60 s after the previous one. */
    traj_row *r = accept("0.001,0,0,1,0,0,0\n0.002,0,0,1,0,0,0\n60.002,0,0,1,0,0,0\n", 3);
    assert_true(r[2].t == 60.002);
    free(r);
    /* 1999.6 us rounds to 2000 us, 1000 us after 1000 us; 1999.4 us rounds to 1999 us. */
    free(accept("0.001,0,0,1,0,0,0\n0.0019996,0,0,1,0,0,0\n", 2));
    refuse("0.001,0,0,1,0,0,0\n0.0019994,0,0,1,0,0,0\n",
           "2: t = 0.0019994 s is 0.000999 s after line 1's t = 0.001 s; each row's t must exceed the previous "
           "by 0.001 s to 60 s (differences rounded to 1 us)");
    refuse("1,0,0,1,0,0,0\n# c\n61.000001,0,0,1,0,0,0\n",
           "3: t = 61.000001 s is 60.000001 s after line 1's t = 1 s");
    refuse("1,0,0,1,0,0,0\n1,0,0,1,0,0,0\n", "2: t = 1 s does not come after line 1's t = 1 s");
    refuse("1,0,0,1,0,0,0\n2,0,0,1,0,0,0\n1.5,0,0,1,0,0,0\n", "3: t = 1.5 s does not come after line 2's t = 2 s");
}

static void test_files_without_rows(void **state)
{
    (void)state;
    refuse("", ": no rows (the file is empty)");
    refuse("\xEF\xBB\xBF", ": no rows (the file is empty)");
    refuse("\n\n", ": no rows (only blank lines, comments or a header)");
    refuse("# nothing\r\n", ": no rows (only blank lines, comments or a header)");
    refuse("t,x,y,z,roll,pitch,yaw\n# none\n", ": no rows (only blank lines, comments or a header)");

    traj_row *rows = (traj_row *)&rows;
    char err[256];
    assert_int_equal(traj_file_read("/nonexistent/traj.csv", &rows, err, sizeof err), -1);
    assert_null(rows);
    assert_string_equal(err, "/nonexistent/traj.csv: cannot open: No such file or directory");

    /* A directory opens, but cannot be read. */
    char dir[] = "/tmp/tse_traj_dir_XXXXXX";
    assert_non_null(mkdtemp(dir));
    assert_int_equal(traj_file_read(dir, &rows, err, sizeof err), -1);
    char want[64];
    snprintf(want, sizeof want, "%s: cannot read", dir);
    assert_memory_equal(err, want, strlen(want));
    rmdir(dir);
}

static void test_long_lines(void **state)
{
    (void)state;
    /* 4096 bytes is the reader's limit: a row padded to exactly that is fine, one byte more is not. */
    enum { MAX = 4096 };
    char *text = malloc(3 * MAX);
    assert_non_null(text);
    const char *row = "0.1,0,0,1,0,0,0";
    strcpy(text, "# c\n");
    size_t n = strlen(text);
    memset(text + n, ' ', MAX - strlen(row));
    n += MAX - strlen(row);
    strcpy(text + n, row);
    strcat(text, "\n");
    free(accept(text, 1));

    strcpy(text, "# c\n0.1,0,0,1,0,0,0\n");
    n = strlen(text);
    memset(text + n, ' ', MAX + 1 - strlen(row));
    n += MAX + 1 - strlen(row);
    strcpy(text + n, "0.2,0,0,1,0,0,0\n0.3,0,0,1,0,0,0\n");
    refuse(text, "3: line longer than 4096 bytes");
    free(text);
}

static void test_row_limit(void **state)
{
    (void)state;
    /* A header and 1,000,001 rows 1 ms apart: the first 1,000,000 are taken, the next is line 1000002. */
    FILE *f;
    strcpy(path, "/tmp/tse_traj_XXXXXX");
    const int fd = mkstemp(path);
    assert_true(fd >= 0);
    f = fdopen(fd, "w");
    assert_non_null(f);
    fputs("t,x,y,z,roll,pitch,yaw\n", f);
    for (long k = 1; k <= TRAJ_FILE_MAX_ROWS + 1; ++k)
        fprintf(f, "%ld.%03ld,0,0,1,0,0,0\n", k / 1000, k % 1000);
    fclose(f);
    traj_row *rows;
    char err[256];
    assert_int_equal(traj_file_read(path, &rows, err, sizeof err), -1);
    char want[128];
    snprintf(want, sizeof want, "%s:1000002: more than 1000000 rows", path);
    assert_string_equal(err, want);
    assert_null(rows);
    unlink(path);
    assert_int_equal(TRAJ_FILE_MAX_ROWS, 1000000);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_rows_values_and_lines),
        cmocka_unit_test(test_crlf_bom_and_header),
        cmocka_unit_test(test_first_line_neither_header_nor_row),
        cmocka_unit_test(test_shifted_and_malformed_columns),
        cmocka_unit_test(test_wire_range),
        cmocka_unit_test(test_time_rules),
        cmocka_unit_test(test_files_without_rows),
        cmocka_unit_test(test_long_lines),
        cmocka_unit_test(test_row_limit),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
