/* Line-by-line input for the host tools' CSV readers.
 *
 * Promise: every line of the stream is returned exactly once, in order, including a last line
 * without a newline and lines that contain NUL bytes (the length is exact), so that a command can
 * write one output line per input line.  A UTF-8 byte order mark (EF BB BF) at the very start of
 * the stream is not part of the first line: editors on Windows write one, and it would otherwise
 * make the first field "not a number".  A line longer than LINE_READER_MAX bytes (the BOM not
 * counted) is returned truncated with *overlong set, and the rest of it is consumed.  Memory is
 * bounded. */
#ifndef TSE_HOST_LINE_READER_H
#define TSE_HOST_LINE_READER_H

#include <stddef.h>
#include <stdio.h>

/* Far more than any row of numbers needs (twelve %.17g numbers take about 300 bytes). */
#define LINE_READER_MAX 4096

#define UTF8_BOM "\xEF\xBB\xBF"
#define UTF8_BOM_LEN 3

typedef struct {
    FILE *f;
    int at_start; /* no byte of the stream read yet: a BOM may come */
    char buf[LINE_READER_MAX + 1];
} line_reader;

void line_reader_init(line_reader *r, FILE *f);

/* Next line: returns 1 with *line (NUL-terminated, newline excluded), *len and *overlong set;
 * 0 at the end of the stream; -1 on a read error. */
int line_reader_next(line_reader *r, const char **line, size_t *len, int *overlong);

/* The next line of a CSV file that holds something (lines blank but for spaces, tabs and a CR, and
 * lines whose first other character is '#', skipped), its 1-based number in *line (counted from 0 before the first
 * call): 1; 0 at the end; -1 with "PATH:LINE: why" (a line longer than LINE_READER_MAX, a NUL
 * byte, more lines than an int counts) or "PATH: cannot read ..." in err. */
int line_reader_next_content(line_reader *r, const char *path, int *line, const char **s, size_t *len, char *err,
                             size_t errlen);

/* For readers that take a whole text at once: UTF8_BOM_LEN when text[0..len) starts with a BOM,
 * else 0. */
size_t utf8_bom_length(const char *text, size_t len);

#endif
