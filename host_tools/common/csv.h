/* Rows of numbers in and out of the host tools.
 *
 * Promise: a row is accepted only when it is exactly a comma-separated list of numbers, each one
 * whole token for strtod (spaces or tabs around a field are allowed), with an optional trailing CR
 * and/or LF.  "nan" and "inf" are numbers here: whether they make sense is the caller's call.
 * A refused row says why and, when one field is at fault, which one (its 1-based column and its
 * text), so that a reader can name the column.  Numbers go out as %.17g, except that every NaN is
 * written "nan" (glibc would write "-nan" for a negative one), so that scripts see one spelling. */
#ifndef TSE_HOST_CSV_H
#define TSE_HOST_CSV_H

#include <stddef.h>
#include <stdio.h>

/* A field of a row: text[0..len), padding excluded, not NUL-terminated. */
typedef struct {
    const char *text;
    size_t len;
} csv_span;

/* Why a row was refused. */
typedef struct {
    const char *why; /* "blank line", "empty field", "not a number", "trailing text",
                      * "too many fields", "field too long", "NUL byte" */
    int column;      /* 1-based column of the field at fault; 0 when no one field is */
    csv_span field;  /* that field's text (for "too many fields", the first one beyond max) */
} csv_error;

/* Parses the row line[0..len) (it may contain NUL bytes, which make it malformed) into at most max
 * numbers.  Returns how many, or -1 for a malformed row with the reason in *e. */
int csv_parse_fields(const char *line, size_t len, double *out, int max, csv_error *e);

/* The same with the reason only, in *why. */
int csv_parse_row(const char *line, size_t len, double *out, int max, const char **why);

/* Parses a NUL-terminated list such as an option's value "1,2,3"; same rules. */
int csv_parse_list(const char *s, double *out, int max, const char **why);

/* Splits line[0..len) (line end dropped) at its commas into fields without their padding; stores
 * the first max of them and returns how many there are (at least 1: a blank line is one empty
 * field). */
int csv_split(const char *line, size_t len, csv_span *fields, int max);

/* Whether the row is exactly the n names given, compared without regard to case, padding allowed
 * ("t, X ,y,..." for {"t", "x", "y", ...}). */
int csv_is_header(const char *line, size_t len, const char *const *names, int n);

/* Whether the row's first field starts as a number does (what tells a row from a would-be header). */
int csv_starts_with_number(const char *line, size_t len);

/* A field as written, made safe to quote in a message: at most CSV_SHOWN_MAX bytes then "...",
 * control bytes as '?'.  Returns buf (cap at least CSV_SHOWN_MAX + 8). */
#define CSV_SHOWN_MAX 40
const char *csv_shown(csv_span f, char *buf, size_t cap);

/* Writes ",x" for each of the n numbers. */
void csv_put_numbers(FILE *f, const double *v, int n);

/* Writes ",nan" n times. */
void csv_put_nans(FILE *f, int n);

/* Writes one number as %.17g with the single NaN spelling. */
void csv_put_number(FILE *f, double x);

#endif
