/* Trajectory file reader: see traj_file.h for the rules. */
#include "traj_file.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "csv.h"
#include "line_reader.h"
#include "text.h"

enum { COLS = 7 };

static const char *const names[COLS] = {"t", "x", "y", "z", "roll", "pitch", "yaw"};
#define NAMES_TEXT "t,x,y,z,roll,pitch,yaw"

long long traj_time_us(double t)
{
    /* Far beyond any valid time (1e6 rows of 60 s are 6e13 us), and the difference of two
     * clamped values still fits: the rules then refuse it as too far apart. */
    const double lim = 1e18;
    const double us = t * 1e6;
    if (!(us < lim))
        return us > 0 ? (long long)lim : -(long long)lim; /* also nan, which the caller refused */
    if (us < -lim)
        return -(long long)lim;
    return llround(us);
}

typedef struct {
    const char *path;
    char *err;
    size_t errlen;
} ctx;

/* "PATH:LINE: what is wrong" in the reader's err; -1. */
#define fail_line(c, line, ...) text_line_error((c)->err, (c)->errlen, (c)->path, line, __VA_ARGS__)

/* Parses and checks one row's numbers (everything but the time).  0, or -1 with the message. */
static int parse_row(const ctx *c, int line, const char *s, size_t len, traj_row *r)
{
    csv_span f[COLS + 1];
    const int cols = csv_split(s, len, f, COLS + 1);
    if (cols != COLS) {
        return fail_line(c, line, "%d column%s, expected 7 (" NAMES_TEXT ")", cols, cols == 1 ? "" : "s");
    }
    double v[COLS];
    csv_error e;
    char buf[CSV_SHOWN_MAX + 8], col[32];
    if (csv_parse_fields(s, len, v, COLS, &e) != COLS) {
        snprintf(col, sizeof col, "column %d (%s)", e.column, e.column >= 1 ? names[e.column - 1] : "?");
        if (!strcmp(e.why, "empty field"))
            return fail_line(c, line, "%s: empty", col);
        if (!strcmp(e.why, "field too long"))
            return fail_line(c, line, "%s: longer than 127 characters", col);
        return fail_line(c, line, "%s: not a number '%s'", col, csv_shown(e.field, buf, sizeof buf));
    }
    for (int k = 0; k < COLS; ++k) {
        snprintf(col, sizeof col, "column %d (%s)", k + 1, names[k]);
        if (!isfinite(v[k]))
            return fail_line(c, line, "%s: not a finite number '%s'", col, csv_shown(f[k], buf, sizeof buf));
        if (k == 0)
            continue;
        const int angle = k >= 4;
        const double lim = angle ? TRAJ_FILE_ANGLE_MAX : TRAJ_FILE_POS_MAX;
        if (!(fabs(v[k]) <= lim))
            return fail_line(c, line,
                             angle ? "%s = %s rad is outside the wire's range -3.141593..3.141593 rad"
                                   : "%s = %s m is outside the wire's range -4..4 m",
                             col, csv_shown(f[k], buf, sizeof buf));
    }
    r->t = v[0];
    memcpy(r->p, v + 1, sizeof r->p);
    r->line = line;
    return 0;
}

/* The time rule against the previous row (NULL for the first).  0, or -1 with the message. */
static int check_time(const ctx *c, const traj_row *r, const traj_row *prev)
{
    /* r is a row parse_row filled (it returned 0); the analyzer, which does not follow the
     * variadic fail_line, takes a failed parse_row for 0 too.
     * NOLINTNEXTLINE(clang-analyzer-core.CallAndMessage) */
    const long long dt = traj_time_us(r->t) - (prev ? traj_time_us(prev->t) : 0);
    if (dt >= TRAJ_FILE_DT_MIN_US && dt <= TRAJ_FILE_DT_MAX_US)
        return 0;
    if (!prev)
        return fail_line(c, r->line,
                         "t = %.9g s: the first row's t must be 0.001 s to 60 s (the time from the moment the "
                         "controller takes it, rounded to 1 us)",
                         r->t);
    if (dt <= 0)
        return fail_line(c, r->line,
                         "t = %.9g s does not come after line %d's t = %.9g s; each row's t must exceed the "
                         "previous by 0.001 s to 60 s",
                         r->t, prev->line, prev->t);
    return fail_line(c, r->line,
                     "t = %.9g s is %.6f s after line %d's t = %.9g s; each row's t must exceed the previous by "
                     "0.001 s to 60 s (differences rounded to 1 us)",
                     r->t, (double)dt * 1e-6, prev->line, prev->t);
}

/* Keeps room for one more row; 0, or -1 when out of memory. */
static int reserve(traj_row **rows, size_t *cap, size_t n)
{
    if (n < *cap)
        return 0;
    size_t want = *cap ? 2 * *cap : 1024;
    if (want > TRAJ_FILE_MAX_ROWS)
        want = TRAJ_FILE_MAX_ROWS;
    traj_row *grown = realloc(*rows, want * sizeof **rows);
    if (!grown)
        return -1;
    *rows = grown;
    *cap = want;
    return 0;
}

/* The whole file: the number of rows, or -1 with the message.  *rows is the caller's to free. */
static int read_rows(const ctx *c, FILE *f, traj_row **rows)
{
    line_reader *rd = malloc(sizeof *rd);
    if (!rd) {
        snprintf(c->err, c->errlen, "%s: out of memory", c->path);
        return -1;
    }
    line_reader_init(rd, f);
    size_t n = 0, cap = 0;
    int line = 0, got, seen_content = 0, rc = -1;
    const char *s;
    size_t len;
    while ((got = line_reader_next_content(rd, c->path, &line, &s, &len, c->err, c->errlen)) == 1) {
        const int first = !seen_content;
        seen_content = 1;
        if (first && csv_is_header(s, len, names, COLS))
            continue;
        if (first && !csv_starts_with_number(s, len)) {
            char buf[CSV_SHOWN_MAX + 8];
            const csv_span whole = {s, len};
            fail_line(c, line, "neither the header " NAMES_TEXT " nor a row of 7 numbers: '%s'",
                      csv_shown(whole, buf, sizeof buf));
            goto out;
        }
        if (n == TRAJ_FILE_MAX_ROWS) {
            fail_line(c, line, "more than %d rows", TRAJ_FILE_MAX_ROWS);
            goto out;
        }
        if (reserve(rows, &cap, n) != 0) {
            snprintf(c->err, c->errlen, "%s: out of memory after %zu rows", c->path, n);
            goto out;
        }
        traj_row *r = &(*rows)[n];
        if (parse_row(c, line, s, len, r) != 0 || check_time(c, r, n ? r - 1 : NULL) != 0)
            goto out;
        ++n;
    }
    if (got < 0)
        goto out;
    if (n == 0) {
        snprintf(c->err, c->errlen, "%s: no rows (%s)", c->path,
                 line == 0 ? "the file is empty" : "only blank lines, comments or a header");
        goto out;
    }
    rc = (int)n;
out:
    free(rd);
    return rc;
}

int traj_file_read(const char *path, traj_row **rows, char *err, size_t errlen)
{
    *rows = NULL;
    const ctx c = {path, err, errlen};
    FILE *f = fopen(path, "rb");
    if (!f) {
        snprintf(err, errlen, "%s: cannot open: %s", path, strerror(errno));
        return -1;
    }
    traj_row *got = NULL;
    const int n = read_rows(&c, f, &got);
    (void)fclose(f); /* read only: all it read is checked */
    if (n < 0) {
        free(got);
        return -1;
    }
    *rows = got;
    return n;
}
