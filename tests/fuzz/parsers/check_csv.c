/* csv.h and tse-kin's row loop (stream.h) against the reference reading of their rules. */
#define _POSIX_C_SOURCE 200809L /* open_memstream */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "checks.h"
#include "csv.h"
#include "fuzz_target.h"
#include "ref_text.h"
#include "stream.h"

enum { MAX_NUMBERS = 16 };

/* csv_put_number's output read back: the same number (every NaN is written "nan": only NaN-ness
 * survives). */
static void check_reprint(const double *v, int n)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    FUZZ_CHECK(f != NULL);
    csv_put_numbers(f, v, n);
    FUZZ_CHECK(fclose(f) == 0);
    FUZZ_CHECK(len >= 2 && buf[0] == ',');
    double back[MAX_NUMBERS];
    const char *why = NULL;
    FUZZ_CHECK(csv_parse_row(buf + 1, len - 1, back, n, &why) == n);
    for (int k = 0; k < n; ++k)
        FUZZ_CHECK(isnan(v[k]) ? isnan(back[k]) : ref_same_double(v[k], back[k]));
    free(buf);
}

void check_csv_row(const char *data, size_t size, unsigned opt)
{
    const int max = 1 + (int)(opt % MAX_NUMBERS);
    double got[MAX_NUMBERS + 1], want[MAX_NUMBERS + 1];
    csv_error e;
    memset(&e, 0x5A, sizeof e);
    const int n = csv_parse_fields(data, size, got, max, &e);
    ref_verdict v;
    const int rn = ref_row(data, size, want, max, &v);
    if (rn >= 0) {
        FUZZ_CHECK(n == rn);
        for (int k = 0; k < n; ++k)
            FUZZ_CHECK(ref_same_double(got[k], want[k]));
        check_reprint(got, n);
        return;
    }
    FUZZ_CHECK(n == -1);
    FUZZ_CHECK(e.column == v.column);
    /* The first field beyond max when it is also empty: either reason names it. */
    const int either = v.column == max + 1 && !strcmp(v.why, "empty field");
    FUZZ_CHECK(!strcmp(e.why, v.why) || (either && !strcmp(e.why, "too many fields")));
    if (v.column > 0)
        FUZZ_CHECK(e.field.text == v.field && e.field.len == v.field_len);
}

/* What the row loop handed the command, in order. */
typedef struct {
    int n;
    double v[MAX_NUMBERS];
} seen_row;

static struct {
    seen_row *rows;
    int count, cap;
} seen;

static void record_row(const kin_run *run, const double *v, int n, FILE *out)
{
    (void)run;
    if (seen.count < seen.cap && n >= 0 && n <= MAX_NUMBERS) {
        seen.rows[seen.count].n = n;
        memcpy(seen.rows[seen.count].v, v, (size_t)n * sizeof *v);
    }
    ++seen.count;
    fputs("row\n", out);
}

/* stream.h: a first line of n_min or n_max names that is not a row of numbers. */
static int ref_header(const ref_line *l, const stream_spec *spec)
{
    enum { MAXF = MAX_NUMBERS + 1 };
    const char *text[MAXF];
    size_t flen[MAXF];
    const int n = ref_fields(l->text, l->len, text, flen, MAXF);
    if (n > MAX_NUMBERS || (n != spec->n_min && n != spec->n_max))
        return 0;
    for (int k = 0; k < n; ++k) {
        const char *s = text[k];
        if (flen[k] == 0 || !((s[0] >= 'a' && s[0] <= 'z') || (s[0] >= 'A' && s[0] <= 'Z') || s[0] == '_'))
            return 0;
        for (size_t i = 1; i < flen[k]; ++i)
            if (!((s[i] >= 'a' && s[i] <= 'z') || (s[i] >= 'A' && s[i] <= 'Z') || (s[i] >= '0' && s[i] <= '9') ||
                  s[i] == '_'))
                return 0;
    }
    double v[MAX_NUMBERS];
    ref_verdict verdict;
    return ref_row(l->text, l->len, v, MAX_NUMBERS, &verdict) < 0; /* "nan,inf,..." is numbers */
}

typedef struct {
    const char *path;
    const stream_spec *spec;
    FILE *out;
    int rc;
} stream_call;

static void run_stream(void *arg)
{
    stream_call *c = arg;
    FILE *in = fopen(c->path, "rb");
    FUZZ_CHECK(in != NULL);
    c->rc = stream_rows(NULL, in, c->out, c->spec);
    fclose(in);
}

void check_kin_stream(const char *data, size_t size, unsigned opt)
{
    /* The three commands' shapes: ik, fk (6 or 12 numbers), jacobian. */
    static const stream_spec specs[] = {
        {6, 6, 6, "H:ik", record_row},
        {6, 12, 6, "H:fk", record_row},
        {6, 6, 42, "H:jacobian", record_row},
    };
    const stream_spec *spec = &specs[opt % 3];

    const int cap = (int)size + 1;
    ref_line *lines = malloc((size_t)cap * sizeof *lines);
    seen.rows = malloc((size_t)cap * sizeof *seen.rows);
    FUZZ_CHECK(lines && seen.rows);
    seen.count = 0;
    seen.cap = cap;
    const int nlines = ref_lines(data, size, lines, cap);

    char *out = NULL;
    size_t out_len = 0;
    stream_call c = {mem_file(data, size), spec, open_memstream(&out, &out_len), -1};
    FUZZ_CHECK(c.out != NULL);
    without_stderr(run_stream, &c);
    FUZZ_CHECK(fclose(c.out) == 0);
    FUZZ_CHECK(c.rc == KIN_EXIT_OK);

    /* The answer to a malformed line. */
    char invalid[16 + 4 * 42];
    strcpy(invalid, "invalid,0");
    for (int k = 0; k < spec->out_numbers; ++k)
        strcat(invalid, ",nan");

    /* One output line per input line, in order. */
    const char *o = out;
    int rows = 0;
    for (int i = 0; i < nlines; ++i) {
        const char *nl = memchr(o, '\n', out_len - (size_t)(o - out));
        FUZZ_CHECK(nl != NULL);
        const size_t olen = (size_t)(nl - o);
        const ref_line *l = &lines[i];
        const char *want = NULL;
        double v[MAX_NUMBERS + 1];
        int n = -1;
        if (i == 0 && !l->overlong && ref_header(l, spec)) {
            want = spec->out_header;
        } else {
            ref_verdict verdict;
            if (!l->overlong)
                n = ref_row(l->text, l->len, v, spec->n_max + 1, &verdict);
            if (n != spec->n_min && n != spec->n_max)
                want = invalid;
        }
        if (want) {
            FUZZ_CHECK(olen == strlen(want) && !memcmp(o, want, olen));
        } else {
            FUZZ_CHECK(olen == 3 && !memcmp(o, "row", 3));
            FUZZ_CHECK(rows < seen.count && seen.rows[rows].n == n);
            for (int k = 0; k < n; ++k)
                FUZZ_CHECK(ref_same_double(seen.rows[rows].v[k], v[k]));
            ++rows;
        }
        o = nl + 1;
    }
    FUZZ_CHECK((size_t)(o - out) == out_len); /* nothing more */
    FUZZ_CHECK(rows == seen.count);
    free(out);
    free(seen.rows);
    free(lines);
}
