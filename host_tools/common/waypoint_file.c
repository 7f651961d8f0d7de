/* Waypoint file reader: see waypoint_file.h for the rules. */
#include "waypoint_file.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "csv.h"
#include "line_reader.h"
#include "text.h"
#include "traj_file.h"

enum { COL_T = 6, COL_V = 7, NAMES = 8 };
static const char *const names[NAMES] = {"x", "y", "z", "roll", "pitch", "yaw", "t", "v"};

typedef struct {
    const char *path;
    char *err;
    size_t errlen;
    int cols;         /* columns of a row */
    int what[NAMES];  /* what column k holds (an index into names) */
} reader;

/* "PATH:LINE: what is wrong" in the reader's err; -1. */
#define fail(r, line, ...) text_line_error((r)->err, (r)->errlen, (r)->path, line, __VA_ARGS__)

static int field_text(csv_span f, char *buf, size_t cap)
{
    if (f.len >= cap)
        return -1;
    memcpy(buf, f.text, f.len);
    buf[f.len] = '\0';
    return 0;
}

/* The header's columns.  0, or -1 with the message. */
static int read_header(reader *r, int line, const char *s, size_t len)
{
    csv_span f[NAMES + 1];
    const int n = csv_split(s, len, f, NAMES + 1);
    int seen[NAMES] = {0};
    char name[16], buf[CSV_SHOWN_MAX + 8];
    for (int k = 0; k < n && k < NAMES + 1; ++k) {
        int id = -1;
        for (int j = 0; j < NAMES && field_text(f[k], name, sizeof name) == 0; ++j)
            if (!strcasecmp(name, names[j]))
                id = j;
        if (id < 0)
            return fail(r, line, "column %d: '%s' is not one of x,y,z,roll,pitch,yaw,t,v (the header names the columns)",
                        k + 1, csv_shown(f[k], buf, sizeof buf));
        if (seen[id]++)
            return fail(r, line, "column %d: '%s' is named twice", k + 1, names[id]);
        r->what[k] = id;
    }
    for (int j = 0; j < COL_T; ++j)
        if (!seen[j])
            return fail(r, line, "the header has no column %s (x,y,z,roll,pitch,yaw are needed; t and v may be added)",
                        names[j]);
    r->cols = n;
    return 0;
}

/* One row; first: it is the first waypoint; prev_t, prev_line: the latest time given before it (the
 * first waypoint's 0 when it gives none). */
static int parse_row(const reader *r, int line, const char *s, size_t len, waypoint_row *w, int first, double prev_t,
                     int prev_line)
{
    csv_span f[NAMES + 1];
    const int n = csv_split(s, len, f, NAMES + 1);
    if (n != r->cols)
        return fail(r, line, "%d column%s, expected %d", n, n == 1 ? "" : "s", r->cols);
    w->t = w->v = NAN;
    w->line = line;
    char tok[128], buf[CSV_SHOWN_MAX + 8];
    for (int k = 0; k < n; ++k) {
        const int id = r->what[k];
        double v;
        if (f[k].len == 0) {
            if (id >= COL_T)
                continue; /* free */
            return fail(r, line, "column %d (%s): empty", k + 1, names[id]);
        }
        if (field_text(f[k], tok, sizeof tok) != 0)
            return fail(r, line, "column %d (%s): longer than 127 characters", k + 1, names[id]);
        if (text_number(tok, &v) != 0)
            return fail(r, line, "column %d (%s): not a finite number '%s'", k + 1, names[id],
                        csv_shown(f[k], buf, sizeof buf));
        if (id < 3 && !(fabs(v) <= TRAJ_FILE_POS_MAX))
            return fail(r, line, "column %d (%s) = %s m is outside the wire's range -4..4 m", k + 1, names[id], tok);
        if (id >= 3 && id < COL_T && !(fabs(v) <= TRAJ_FILE_ANGLE_MAX))
            return fail(r, line, "column %d (%s) = %s rad is outside the wire's range -3.141593..3.141593 rad", k + 1,
                        names[id], tok);
        if (id == COL_V && !(v > 0.0))
            return fail(r, line, "column %d (v) = %s: a speed cap must be above 0 m/s", k + 1, tok);
        if (id < COL_T)
            w->pose[id] = v;
        else if (id == COL_T)
            w->t = v;
        else
            w->v = v;
    }
    if (!isnan(w->t)) {
        if (first && w->t != 0.0)
            return fail(r, line, "t = %.9g s: the first waypoint is where the path starts, its t is 0 (or empty)", w->t);
        if (!first && !(w->t > prev_t))
            return fail(r, line, "t = %.9g s does not come after line %d's t = %.9g s", w->t, prev_line, prev_t);
    }
    return 0;
}

static int read_all(reader *r, FILE *f, waypoint_row **rows)
{
    line_reader *rd = malloc(sizeof *rd);
    if (!rd) {
        snprintf(r->err, r->errlen, "%s: out of memory", r->path);
        return -1;
    }
    line_reader_init(rd, f);
    size_t n = 0, cap = 0;
    int line = 0, got, seen = 0, rc = -1;
    double last_t = 0.0;
    int last_line = 0;
    const char *s;
    size_t len;
    r->cols = COL_T;
    for (int k = 0; k < NAMES; ++k)
        r->what[k] = k;
    while ((got = line_reader_next_content(rd, r->path, &line, &s, &len, r->err, r->errlen)) == 1) {
        if (!seen++ && !csv_starts_with_number(s, len)) {
            if (read_header(r, line, s, len) != 0)
                goto out;
            continue;
        }
        if (n == WAYPOINT_FILE_MAX_ROWS) {
            fail(r, line, "more than %d waypoints", WAYPOINT_FILE_MAX_ROWS);
            goto out;
        }
        if (n == cap) {
            cap = cap ? 2 * cap : 256;
            waypoint_row *grown = realloc(*rows, cap * sizeof **rows);
            if (!grown) {
                snprintf(r->err, r->errlen, "%s: out of memory after %zu rows", r->path, n);
                goto out;
            }
            *rows = grown;
        }
        if (parse_row(r, line, s, len, &(*rows)[n], n == 0, last_t, last_line) != 0)
            goto out;
        if (n == 0 || !isnan((*rows)[n].t)) {
            last_t = isnan((*rows)[n].t) ? 0.0 : (*rows)[n].t;
            last_line = line;
        }
        ++n;
    }
    if (got < 0)
        goto out;
    if (n < 2) {
        snprintf(r->err, r->errlen, "%s: %zu waypoint%s: a path needs at least 2", r->path, n, n == 1 ? "" : "s");
        goto out;
    }
    rc = (int)n;
out:
    free(rd);
    return rc;
}

int waypoint_file_read(const char *path, waypoint_row **rows, char *err, size_t errlen)
{
    *rows = NULL;
    reader r = {path, err, errlen, 0, {0}};
    FILE *f = fopen(path, "rb");
    if (!f) {
        snprintf(err, errlen, "%s: cannot open: %s", path, strerror(errno));
        return -1;
    }
    const int n = read_all(&r, f, rows);
    (void)fclose(f);
    if (n < 0) {
        free(*rows);
        *rows = NULL;
    }
    return n;
}
