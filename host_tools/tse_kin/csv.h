/* Rows of numbers in and out of tse-kin.
 *
 * Promise: a row is accepted only when it is exactly a comma-separated list of numbers, each one
 * whole token for strtod (spaces or tabs around a field are allowed), with an optional trailing CR
 * and/or LF.  "nan" and "inf" are numbers here: whether they make sense is the library's call.
 * Numbers go out as %.17g, except that every NaN is written "nan" (glibc would write "-nan" for a
 * negative one), so that scripts see one spelling. */
#ifndef TSE_KIN_CSV_H
#define TSE_KIN_CSV_H

#include <stddef.h>
#include <stdio.h>

/* Parses the row line[0..len) (it may contain NUL bytes, which make it malformed) into at most max
 * numbers.  Returns how many, or -1 for a malformed row with a short reason in *why: "blank line",
 * "empty field", "not a number", "trailing text", "too many fields", "field too long", "NUL byte". */
int csv_parse_row(const char *line, size_t len, double *out, int max, const char **why);

/* Parses a NUL-terminated list such as an option's value "1,2,3"; same rules. */
int csv_parse_list(const char *s, double *out, int max, const char **why);

/* Writes ",x" for each of the n numbers. */
void csv_put_numbers(FILE *f, const double *v, int n);

/* Writes ",nan" n times. */
void csv_put_nans(FILE *f, int n);

/* Writes one number as %.17g with the single NaN spelling. */
void csv_put_number(FILE *f, double x);

#endif
