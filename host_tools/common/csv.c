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

/* The line terminator is not part of the row. */
static size_t without_line_end(const char *line, size_t len)
{
    if (len > 0 && line[len - 1] == '\n')
        --len;
    if (len > 0 && line[len - 1] == '\r')
        --len;
    return len;
}

/* The field starting at line[start], up to the next comma or len, without its padding; returns
 * where it ends (the comma or len). */
static size_t next_field(const char *line, size_t len, size_t start, csv_span *f)
{
    size_t i = start;
    while (i < len && line[i] != ',')
        ++i;
    size_t a = start, b = i;
    while (a < b && is_pad(line[a]))
        ++a;
    while (b > a && is_pad(line[b - 1]))
        --b;
    f->text = line + a;
    f->len = b - a;
    return i;
}

static int refuse(csv_error *e, const char *why, int column, csv_span field)
{
    e->why = why;
    e->column = column;
    e->field = field;
    return -1;
}

int csv_parse_fields(const char *line, size_t len, double *out, int max, csv_error *e)
{
    const csv_span none = {line, 0};
    len = without_line_end(line, len);
    if (memchr(line, '\0', len))
        return refuse(e, "NUL byte", 0, none);
    size_t i = 0;
    while (i < len && is_pad(line[i]))
        ++i;
    if (i == len)
        return refuse(e, "blank line", 0, none);
    int n = 0;
    i = 0;
    for (;;) {
        csv_span f;
        i = next_field(line, len, i, &f);
        const int column = n + 1;
        if (f.len == 0)
            return refuse(e, "empty field", column, f);
        if (n == max)
            return refuse(e, "too many fields", column, f);
        char tok[FIELD_MAX];
        if (f.len >= sizeof tok)
            return refuse(e, "field too long", column, f);
        memcpy(tok, f.text, f.len);
        tok[f.len] = '\0';
        char *end;
        const double x = strtod(tok, &end);
        if (end == tok || isspace((unsigned char)tok[0]))
            return refuse(e, "not a number", column, f);
        if (*end != '\0')
            return refuse(e, "trailing text", column, f);
        out[n++] = x;
        if (i == len)
            return n;
        ++i; /* the comma */
    }
}

int csv_parse_row(const char *line, size_t len, double *out, int max, const char **why)
{
    csv_error e;
    const int n = csv_parse_fields(line, len, out, max, &e);
    if (n < 0)
        *why = e.why;
    return n;
}

int csv_parse_list(const char *s, double *out, int max, const char **why)
{
    return csv_parse_row(s, strlen(s), out, max, why);
}

int csv_split(const char *line, size_t len, csv_span *fields, int max)
{
    len = without_line_end(line, len);
    int n = 0;
    for (size_t i = 0;; ++i) {
        csv_span f;
        i = next_field(line, len, i, &f);
        if (n < max)
            fields[n] = f;
        ++n;
        if (i == len)
            return n;
    }
}

int csv_is_header(const char *line, size_t len, const char *const *names, int n)
{
    enum { MAX_NAMES = 32 };
    csv_span f[MAX_NAMES];
    if (n > MAX_NAMES || csv_split(line, len, f, MAX_NAMES) != n)
        return 0;
    for (int k = 0; k < n; ++k) {
        if (f[k].len != strlen(names[k]))
            return 0;
        for (size_t c = 0; c < f[k].len; ++c)
            if (tolower((unsigned char)f[k].text[c]) != tolower((unsigned char)names[k][c]))
                return 0;
    }
    return 1;
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

const char *csv_shown(csv_span f, char *buf, size_t cap)
{
    size_t n = 0;
    for (size_t i = 0; i < f.len && n + 4 < cap; ++i) {
        if (i == CSV_SHOWN_MAX) {
            memcpy(buf + n, "...", 3);
            n += 3;
            break;
        }
        const unsigned char c = (unsigned char)f.text[i];
        buf[n++] = (char)(c < 0x20 || c == 0x7f ? '?' : c);
    }
    buf[n] = '\0';
    return buf;
}

int csv_starts_with_number(const char *line, size_t len)
{
    csv_span f[1];
    csv_split(line, len, f, 1);
    char tok[64];
    if (f[0].len == 0 || f[0].len >= sizeof tok)
        return f[0].len != 0;
    memcpy(tok, f[0].text, f[0].len);
    tok[f[0].len] = '\0';
    char *end;
    (void)strtod(tok, &end);
    return end != tok;
}
