/* The row loop shared by ik, fk and jacobian.
 *
 * Promise: one output line per input line, in order.  The first line may be a header: as many
 * names (a letter or '_', then letters, digits, '_') as a row takes numbers; it is answered by
 * the command's output header.  A row that does not parse, or parses to a field count the command
 * does not take, is answered "invalid,0" and `out_numbers` nans without calling the command; the
 * loop goes on to the end of the input.  The first few malformed lines are reported on stderr
 * with their line number.  A UTF-8 BOM at the start of the input is skipped (line_reader). */
#ifndef TSE_KIN_STREAM_H
#define TSE_KIN_STREAM_H

#include <stdio.h>

#include "commands.h"

/* Answers one well-formed row v[0..n): writes the whole output line, newline included. */
typedef void (*stream_row_fn)(const kin_run *run, const double *v, int n, FILE *out);

/* What a command reads and writes: field counts taken (n_min or n_max, equal for one count), the
 * numbers after status,scissor on every output line, and the output's header line (no newline). */
typedef struct {
    int n_min, n_max;
    int out_numbers;
    const char *out_header;
    stream_row_fn fn;
} stream_spec;

/* Returns a KIN_EXIT_* code: OK at the end of the input, FILE when reading or writing failed. */
int stream_rows(const kin_run *run, FILE *in, FILE *out, const stream_spec *spec);

/* Whether line[0..len) is a header of n_min or n_max names (see above). */
int stream_is_header(const char *line, size_t len, int n_min, int n_max);

#endif
