/* The row loop shared by ik, fk and jacobian.
 *
 * Promise: one output line per input line, in order.  A row that does not parse, or parses to a
 * field count the command does not take, is answered "invalid,0" and `out_numbers` nans without
 * calling the command; the loop goes on to the end of the input.  The first few malformed lines
 * are reported on stderr with their line number. */
#ifndef TSE_KIN_STREAM_H
#define TSE_KIN_STREAM_H

#include <stdio.h>

#include "commands.h"

/* Answers one well-formed row v[0..n): writes the whole output line, newline included. */
typedef void (*stream_row_fn)(const kin_run *run, const double *v, int n, FILE *out);

/* Field counts taken: n_min or n_max (equal for one count).  Returns a KIN_EXIT_* code: OK at the
 * end of the input, FILE when reading or writing failed. */
int stream_rows(const kin_run *run, FILE *in, FILE *out, int n_min, int n_max, int out_numbers, stream_row_fn fn);

#endif
