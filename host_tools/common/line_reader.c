/* Bounded line reader: see line_reader.h for the promise. */
#define _POSIX_C_SOURCE 200809L /* getc_unlocked: one thread reads, no locking per byte */
#include "line_reader.h"

#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <string.h>

#include "text.h"

void line_reader_init(line_reader *r, FILE *f)
{
    r->f = f;
    r->at_start = 1;
    r->buf[0] = '\0';
}

size_t utf8_bom_length(const char *text, size_t len)
{
    return len >= UTF8_BOM_LEN && !memcmp(text, UTF8_BOM, UTF8_BOM_LEN) ? UTF8_BOM_LEN : 0;
}

int line_reader_next(line_reader *r, const char **line, size_t *len, int *overlong)
{
    /* Byte by byte rather than fgets: fgets cannot tell an embedded NUL from the end of the line,
     * and a NUL would then make one line look like two, or swallow the next one. */
    size_t n = 0;
    int ch, any = 0;
    int bom_possible = r->at_start;
    r->at_start = 0;
    *overlong = 0;
    while ((ch = getc_unlocked(r->f)) != EOF) {
        any = 1;
        if (ch == '\n')
            break;
        if (n < LINE_READER_MAX)
            r->buf[n++] = (char)ch;
        else
            *overlong = 1;
        /* Dropped as soon as it is complete, so that it counts against no line's length, and a
         * stream of nothing but a BOM has no line at all. */
        if (bom_possible && n == UTF8_BOM_LEN) {
            bom_possible = 0;
            if (utf8_bom_length(r->buf, n)) {
                n = 0;
                any = 0;
            }
        }
    }
    if (ch == EOF && ferror(r->f))
        return -1;
    if (!any)
        return 0;
    r->buf[n] = '\0';
    *line = r->buf;
    *len = n;
    return 1;
}

/* Blank (spaces, tabs, a CR) or a comment (its first other character '#'). */
static int blank_or_comment(const char *s, size_t len)
{
    size_t i = 0;
    while (i < len && (s[i] == ' ' || s[i] == '\t' || s[i] == '\r'))
        ++i;
    return i == len || s[i] == '#';
}

int line_reader_next_content(line_reader *r, const char *path, int *line, const char **s, size_t *len, char *err,
                             size_t errlen)
{
    int got, overlong;
    while ((got = line_reader_next(r, s, len, &overlong)) == 1) {
        if (*line == INT_MAX) { /* a row's line must fit an int */
            snprintf(err, errlen, "%s: more than %d lines", path, INT_MAX);
            return -1;
        }
        ++*line;
        if (overlong)
            return text_line_error(err, errlen, path, *line, "line longer than %d bytes", LINE_READER_MAX);
        if (memchr(*s, '\0', *len))
            return text_line_error(err, errlen, path, *line, "NUL byte in the line (not a text file?)");
        if (!blank_or_comment(*s, *len))
            return 1;
    }
    if (got < 0)
        snprintf(err, errlen, "%s: cannot read after line %d: %s", path, *line, strerror(errno));
    return got;
}
