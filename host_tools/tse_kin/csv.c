/* Row parsing and number formatting: see csv.h for the promise. */
#include "csv.h"

#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* strtod itself skips any leading whitespace ("\v", "\f", ...); a field may only be padded by these. */
static int is_pad(char c)
{
    return c == ' ' || c == '\t';
}

/* strtod needs a NUL-terminated token: copy one field at a time, which also keeps strtod from
 * reading past the row. */
enum { FIELD_MAX = 128 };

int csv_parse_row(const char *line, size_t len, double *out, int max, const char **why)
{
    /* The line terminator is not part of the row. */
    if (len > 0 && line[len - 1] == '\n')
        --len;
    if (len > 0 && line[len - 1] == '\r')
        --len;
    if (memchr(line, '\0', len)) {
        *why = "NUL byte";
        return -1;
    }
    size_t i = 0;
    while (i < len && is_pad(line[i]))
        ++i;
    if (i == len) {
        *why = "blank line";
        return -1;
    }
    int n = 0;
    i = 0;
    for (;;) {
        const size_t start = i;
        while (i < len && line[i] != ',')
            ++i;
        /* line[start..i) is one field, padding included. */
        size_t a = start, b = i;
        while (a < b && is_pad(line[a]))
            ++a;
        while (b > a && is_pad(line[b - 1]))
            --b;
        if (a == b) {
            *why = "empty field";
            return -1;
        }
        if (n == max) {
            *why = "too many fields";
            return -1;
        }
        char tok[FIELD_MAX];
        if (b - a >= sizeof tok) {
            *why = "field too long";
            return -1;
        }
        memcpy(tok, line + a, b - a);
        tok[b - a] = '\0';
        char *end;
        const double x = strtod(tok, &end);
        if (end == tok || isspace((unsigned char)tok[0])) {
            *why = "not a number";
            return -1;
        }
        if (*end != '\0') {
            *why = "trailing text";
            return -1;
        }
        out[n++] = x;
        if (i == len)
            return n;
        ++i; /* the comma */
    }
}

int csv_parse_list(const char *s, double *out, int max, const char **why)
{
    return csv_parse_row(s, strlen(s), out, max, why);
}

void csv_put_number(FILE *f, double x)
{
    if (isnan(x))
        fputs("nan", f);
    else
        fprintf(f, "%.17g", x);
}

void csv_put_numbers(FILE *f, const double *v, int n)
{
    for (int k = 0; k < n; ++k) {
        fputc(',', f);
        csv_put_number(f, v[k]);
    }
}

void csv_put_nans(FILE *f, int n)
{
    for (int k = 0; k < n; ++k)
        fputs(",nan", f);
}
