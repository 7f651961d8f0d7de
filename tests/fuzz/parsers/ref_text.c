/* The documented text rules, read independently of the parsers (see ref_text.h). */
#include "ref_text.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "line_reader.h" /* LINE_READER_MAX: the documented bound, not its code */

int ref_lines(const char *data, size_t size, ref_line *lines, int max)
{
    size_t i = 0;
    if (size >= 3 && !memcmp(data, "\xEF\xBB\xBF", 3))
        i = 3;
    int n = 0;
    while (i < size) {
        const char *nl = memchr(data + i, '\n', size - i);
        const size_t end = nl ? (size_t)(nl - data) : size;
        if (n < max) {
            const size_t len = end - i;
            lines[n].text = data + i;
            lines[n].overlong = len > LINE_READER_MAX;
            lines[n].len = lines[n].overlong ? LINE_READER_MAX : len;
        }
        ++n;
        i = end + 1; /* past the newline; past the end for a last line without one */
    }
    return n;
}

static int is_pad(char c)
{
    return c == ' ' || c == '\t';
}

/* csv.h: "an optional trailing CR and/or LF". */
static size_t row_end(const char *line, size_t len)
{
    if (len && line[len - 1] == '\n')
        --len;
    if (len && line[len - 1] == '\r')
        --len;
    return len;
}

int ref_fields(const char *line, size_t len, const char **text, size_t *flen, int max)
{
    len = row_end(line, len);
    int n = 0;
    size_t start = 0;
    for (;;) {
        size_t end = start;
        while (end < len && line[end] != ',')
            ++end;
        size_t a = start, b = end;
        while (a < b && is_pad(line[a]))
            ++a;
        while (b > a && is_pad(line[b - 1]))
            --b;
        if (n < max) {
            text[n] = line + a;
            flen[n] = b - a;
        }
        ++n;
        if (end >= len)
            return n;
        start = end + 1;
    }
}

/* A field as a C string for strtod; fields are at most a stream's length. */
static char *field_copy(const char *text, size_t len)
{
    static char buf[1 << 16];
    if (len >= sizeof buf)
        len = sizeof buf - 1;
    memcpy(buf, text, len);
    buf[len] = '\0';
    return buf;
}

int ref_number(const char *text, size_t len, double *out)
{
    if (len == 0 || isspace((unsigned char)text[0]) || memchr(text, '\0', len))
        return 0;
    char *s = field_copy(text, len), *end;
    *out = strtod(s, &end);
    return end != s && *end == '\0';
}

int ref_finite_number(const char *text, size_t len, double *out)
{
    if (len == 0 || memchr(text, '\0', len))
        return 0;
    char *s = field_copy(text, len), *end;
    errno = 0;
    const double x = strtod(s, &end);
    if (end == s || *end != '\0' || errno == ERANGE || !isfinite(x))
        return 0;
    *out = x;
    return 1;
}

const char *ref_trim(const char *text, size_t *len)
{
    size_t a = 0, b = *len;
    while (a < b && isspace((unsigned char)text[a]))
        ++a;
    while (b > a && isspace((unsigned char)text[b - 1]))
        --b;
    *len = b - a;
    return text + a;
}

int ref_same_double(double a, double b)
{
    return !memcmp(&a, &b, sizeof a);
}

static int refuse(ref_verdict *v, const char *why, int column, const char *field, size_t len)
{
    v->why = why;
    v->column = column;
    v->field = field;
    v->field_len = len;
    return -1;
}

int ref_row(const char *line, size_t len, double *out, int max, ref_verdict *v)
{
    refuse(v, NULL, 0, line, 0);
    const size_t body = row_end(line, len);
    if (memchr(line, '\0', body))
        return refuse(v, "NUL byte", 0, line, 0);
    size_t k = 0;
    while (k < body && is_pad(line[k]))
        ++k;
    if (k == body)
        return refuse(v, "blank line", 0, line, 0);
    enum { MAXF = 64 };
    const char *text[MAXF];
    size_t flen[MAXF];
    const int n = ref_fields(line, len, text, flen, MAXF);
    for (int c = 0; c < n && c < MAXF; ++c) {
        if (flen[c] == 0)
            return refuse(v, "empty field", c + 1, text[c], 0);
        if (c == max)
            return refuse(v, "too many fields", c + 1, text[c], flen[c]);
        if (flen[c] > REF_FIELD_MAX)
            return refuse(v, "field too long", c + 1, text[c], flen[c]);
        if (!ref_number(text[c], flen[c], &out[c])) {
            /* strtod reads some of it (trailing text) or none (not a number) */
            char *s = field_copy(text[c], flen[c]), *end;
            (void)strtod(s, &end);
            const int none = end == s || isspace((unsigned char)s[0]);
            return refuse(v, none ? "not a number" : "trailing text", c + 1, text[c], flen[c]);
        }
    }
    if (n > MAXF) /* more fields than max ever is (max < MAXF): refused before this */
        return refuse(v, "too many fields", max + 1, text[max], flen[max]);
    return n;
}
