/* Row loop: see stream.h for the promise. */
#include "stream.h"

#include <ctype.h>

#include "csv.h"
#include "line_reader.h"

/* Enough to see what is wrong with an input without burying the terminal. */
enum { REPORT_MAX = 5, FIELDS_MAX = 16 };

static void report(long lineno, const char *why, long *reported)
{
    if (*reported < REPORT_MAX)
        fprintf(stderr, "tse-kin: stdin:%ld: %s: answered invalid\n", lineno, why);
    else if (*reported == REPORT_MAX)
        fprintf(stderr, "tse-kin: further malformed lines are answered invalid without a message\n");
    ++*reported;
}

static int is_name(csv_span f)
{
    if (f.len == 0 || !(isalpha((unsigned char)f.text[0]) || f.text[0] == '_'))
        return 0;
    for (size_t i = 1; i < f.len; ++i)
        if (!(isalnum((unsigned char)f.text[i]) || f.text[i] == '_'))
            return 0;
    return 1;
}

int stream_is_header(const char *line, size_t len, int n_min, int n_max)
{
    csv_span f[FIELDS_MAX];
    const int n = csv_split(line, len, f, FIELDS_MAX);
    if (n > FIELDS_MAX || (n != n_min && n != n_max))
        return 0;
    /* A row of nan and inf is numbers, not names: the library answers it. */
    double v[FIELDS_MAX];
    const char *why;
    if (csv_parse_row(line, len, v, FIELDS_MAX, &why) >= 0)
        return 0;
    for (int k = 0; k < n; ++k)
        if (!is_name(f[k]))
            return 0;
    return 1;
}

int stream_rows(const kin_run *run, FILE *in, FILE *out, const stream_spec *spec)
{
    static line_reader reader; /* one 4 KiB buffer, reused for every line */
    line_reader_init(&reader, in);
    long lineno = 0, reported = 0;
    const char *line;
    size_t len;
    int overlong, got;
    while ((got = line_reader_next(&reader, &line, &len, &overlong)) == 1) {
        ++lineno;
        if (lineno == 1 && !overlong && stream_is_header(line, len, spec->n_min, spec->n_max)) {
            fprintf(out, "%s\n", spec->out_header);
            continue;
        }
        double v[FIELDS_MAX];
        const char *why = "line too long";
        /* One field more than taken is read, so that a long row is told from a short one. */
        const int n = overlong ? -1 : csv_parse_row(line, len, v, spec->n_max + 1, &why);
        char count_why[64];
        if (n >= 0 && n != spec->n_min && n != spec->n_max) {
            if (spec->n_min == spec->n_max)
                snprintf(count_why, sizeof count_why, "%d numbers where %d are taken", n, spec->n_min);
            else
                snprintf(count_why, sizeof count_why, "%d numbers where %d or %d are taken", n, spec->n_min,
                         spec->n_max);
            why = count_why;
        }
        if (n < 0 || (n != spec->n_min && n != spec->n_max)) {
            report(lineno, why, &reported);
            fputs("invalid,0", out);
            csv_put_nans(out, spec->out_numbers);
            fputc('\n', out);
            continue;
        }
        spec->fn(run, v, n, out);
    }
    if (got < 0) {
        fprintf(stderr, "tse-kin: error reading stdin after line %ld\n", lineno);
        return KIN_EXIT_FILE;
    }
    if (fflush(out) != 0 || ferror(out)) {
        fprintf(stderr, "tse-kin: error writing the output\n");
        return KIN_EXIT_FILE;
    }
    return KIN_EXIT_OK;
}
