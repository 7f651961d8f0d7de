/* Bounded line reader: see line_reader.h for the promise. */
#define _POSIX_C_SOURCE 200809L /* getc_unlocked: one thread reads, no locking per byte */
#include "line_reader.h"

#include <string.h>

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
