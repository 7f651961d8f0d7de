/* Strict parsing of one input row: exactly n or exactly m comma-separated numbers, nothing else. */
#ifndef TSE_KIN_CSV_H
#define TSE_KIN_CSV_H

#include <stddef.h>

/* Parses up to max numbers from line (a trailing CR or LF is allowed).  Returns how many, or -1
 * for a malformed row (an empty field, a non-number, trailing text, more than max fields) with
 * the reason in why.  "nan" and "inf" parse: the library decides what they mean. */
int csv_parse_row(const char *line, double *out, int max, const char **why);

#endif
