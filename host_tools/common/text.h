/* Small text rules every host tool's parsers share, so that a value means the same in a
 * parameter file, on a command line and in a CSV row. */
#ifndef TSE_HOST_TEXT_H
#define TSE_HOST_TEXT_H

/* Strips blanks (isspace) from both ends in place; returns the first kept character. */
char *text_trim(char *s);

/* The whole of s is one finite number for strtod (which may skip leading blanks): "", "1.5x",
 * "nan", "inf" and "1e999" (ERANGE, also an underflow) are refused.  Returns 0 with *out, or -1. */
int text_number(const char *s, double *out);

/* The same rule with blanks allowed after the number too: a value in a `key = value` file. */
int text_value(const char *s, double *out);

#include <stddef.h>

/* Writes "PATH:LINE: " and the formatted message into err (what every file reader's refusal reads
 * like).  Returns -1, so that a reader can `return text_line_error(...)`. */
int text_line_error(char *err, size_t errlen, const char *path, int line, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));

#endif
