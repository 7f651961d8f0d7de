/* traj_file.h's rules read independently: the rows a file gives, or the first line it is refused
 * at, compared with what traj_file_read says. */
#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "checks.h"
#include "fuzz_target.h"
#include "ref_text.h"
#include "traj_file.h"

enum { COLS = 7 };

static int is_blank_or_comment(const ref_line *l)
{
    size_t i = 0;
    while (i < l->len && (l->text[i] == ' ' || l->text[i] == '\t' || l->text[i] == '\r'))
        ++i;
    return i == l->len || l->text[i] == '#';
}

static int is_header(const ref_line *l)
{
    static const char *const names[COLS] = {"t", "x", "y", "z", "roll", "pitch", "yaw"};
    const char *text[COLS + 1];
    size_t len[COLS + 1];
    if (ref_fields(l->text, l->len, text, len, COLS + 1) != COLS)
        return 0;
    for (int k = 0; k < COLS; ++k) {
        if (len[k] != strlen(names[k]))
            return 0;
        for (size_t i = 0; i < len[k]; ++i)
            if (tolower((unsigned char)text[k][i]) != names[k][i])
                return 0;
    }
    return 1;
}

/* One row by the rules: 7 numbers, finite, inside the wire's ranges. */
static int row_ok(const ref_line *l, traj_row *r, int lineno)
{
    double v[COLS];
    ref_verdict why;
    if (ref_row(l->text, l->len, v, COLS, &why) != COLS)
        return 0;
    for (int k = 0; k < COLS; ++k) {
        if (!isfinite(v[k]))
            return 0;
        if (k >= 1 && !(fabs(v[k]) <= (k >= 4 ? TRAJ_FILE_ANGLE_MAX : TRAJ_FILE_POS_MAX)))
            return 0;
    }
    r->t = v[0];
    memcpy(r->p, v + 1, sizeof r->p);
    r->line = lineno;
    return 1;
}

/* traj_time_us's promise on its own: t in microseconds rounded to the nearest whole one. */
static void check_time_us(double t)
{
    const long long us = traj_time_us(t);
    const long double exact = (long double)t * 1e6L;
    FUZZ_CHECK(fabsl((long double)us - exact) <= 0.5L + fabsl(exact) * 0x1p-50L);
}

void check_traj_file(const char *data, size_t size, unsigned opt)
{
    (void)opt;
    const int cap = (int)size + 1;
    ref_line *lines = malloc((size_t)cap * sizeof *lines);
    traj_row *want = malloc((size_t)cap * sizeof *want);
    FUZZ_CHECK(lines && want);
    const int nlines = ref_lines(data, size, lines, cap);

    /* The rows, or the first line that breaks a rule (0: none). */
    int nwant = 0, bad = 0, content = 0;
    for (int i = 0; i < nlines && !bad; ++i) {
        const ref_line *l = &lines[i];
        const int lineno = i + 1;
        if (l->overlong || memchr(l->text, '\0', l->len)) {
            bad = lineno;
            break;
        }
        if (is_blank_or_comment(l))
            continue;
        if (!content++ && is_header(l))
            continue;
        traj_row *r = &want[nwant];
        if (!row_ok(l, r, lineno)) {
            bad = lineno;
            break;
        }
        const long long dt = traj_time_us(r->t) - (nwant ? traj_time_us(want[nwant - 1].t) : 0);
        if (dt < TRAJ_FILE_DT_MIN_US || dt > TRAJ_FILE_DT_MAX_US) {
            bad = lineno;
            break;
        }
        ++nwant;
    }

    const char *path = mem_file(data, size);
    traj_row canary, *rows = &canary;
    char err[512];
    memset(err, 'Z', sizeof err);
    const int n = traj_file_read(path, &rows, err, sizeof err);
    if (bad || nwant == 0) {
        FUZZ_CHECK(n == -1 && rows == NULL);
        FUZZ_CHECK(message_line(err, sizeof err, path) == bad);
    } else {
        FUZZ_CHECK(n == nwant && rows != NULL);
        for (int k = 0; k < n; ++k) {
            FUZZ_CHECK(rows[k].line == want[k].line);
            FUZZ_CHECK(ref_same_double(rows[k].t, want[k].t));
            for (int j = 0; j < 6; ++j)
                FUZZ_CHECK(ref_same_double(rows[k].p[j], want[k].p[j]));
            check_time_us(rows[k].t);
        }
        free(rows);
    }
    free(want);
    free(lines);
}
