/* The fuzz target's own reading of the host parsers' documented text rules, written from their
 * headers (line_reader.h, csv.h, text.h), sharing no code with them: what the parsers' answers are
 * compared against.
 *
 * ref_lines splits a stream as line_reader.h promises (a BOM at the very start dropped, lines at
 * LF, a last line without LF kept, a line beyond LINE_READER_MAX bytes truncated and flagged).
 * ref_row judges one row as csv.h promises, and also says why it refuses, so that the reason and
 * the column a parser gives can be checked. */
#ifndef FUZZ_REF_TEXT_H
#define FUZZ_REF_TEXT_H

#include <stddef.h>

/* The longest field csv.c reads (its FIELD_MAX - 1): longer ones are refused as "field too long",
 * as traj_file.h's messages say ("longer than 127 characters"). */
#define REF_FIELD_MAX 127

typedef struct {
    const char *text; /* into the stream, newline excluded */
    size_t len;       /* at most LINE_READER_MAX */
    int overlong;     /* the line was longer than LINE_READER_MAX: text is its start */
} ref_line;

/* The lines of data[0..size), at most max stored; returns how many there are. */
int ref_lines(const char *data, size_t size, ref_line *lines, int max);

/* Why ref_row refused a row (the csv.h words), and the field at fault. */
typedef struct {
    const char *why;   /* NULL when accepted */
    int column;        /* 1-based, 0 when no one field is at fault */
    const char *field; /* its text (padding excluded) and length */
    size_t field_len;
} ref_verdict;

/* Judges line[0..len) as one row of at most max numbers: returns how many (values in out), or -1
 * with the reason in *v. */
int ref_row(const char *line, size_t len, double *out, int max, ref_verdict *v);

/* The fields of a row (line end and padding dropped), at most max stored; returns how many. */
int ref_fields(const char *line, size_t len, const char **text, size_t *flen, int max);

/* Whether text[0..len) is one whole strtod token (no blank first), and its value. */
int ref_number(const char *text, size_t len, double *out);

/* The same, but also refusing what text.h's text_number refuses: not finite, out of range
 * (ERANGE, underflow too).  Leading and trailing isspace blanks are the caller's to strip. */
int ref_finite_number(const char *text, size_t len, double *out);

/* Strips isspace blanks from both ends of text[0..*len): returns the new start, updates *len. */
const char *ref_trim(const char *text, size_t *len);

/* Bitwise equality, so that a NaN equals the same NaN and 0 is not -0. */
int ref_same_double(double a, double b);

#endif
