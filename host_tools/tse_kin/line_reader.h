/* Line-by-line input for the streaming commands.
 *
 * Promise: every line of the stream is returned exactly once, in order, including a last line
 * without a newline and lines that contain NUL bytes (the length is exact), so that a command can
 * write one output line per input line.  A line longer than LINE_READER_MAX bytes is returned
 * truncated with *overlong set, and the rest of it is consumed.  Memory is bounded. */
#ifndef TSE_KIN_LINE_READER_H
#define TSE_KIN_LINE_READER_H

#include <stddef.h>
#include <stdio.h>

/* Far more than any row of numbers needs (twelve %.17g numbers take about 300 bytes). */
#define LINE_READER_MAX 4096

typedef struct {
    FILE *f;
    char buf[LINE_READER_MAX + 1];
} line_reader;

void line_reader_init(line_reader *r, FILE *f);

/* Next line: returns 1 with *line (NUL-terminated, newline excluded), *len and *overlong set;
 * 0 at the end of the stream; -1 on a read error. */
int line_reader_next(line_reader *r, const char **line, size_t *len, int *overlong);

#endif
