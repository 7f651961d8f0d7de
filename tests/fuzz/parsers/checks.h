/* The parsers target's cases, one per host text parser; each feeds it data[0..size) and checks the
 * parser's documented promises (fuzz_parsers.c says which byte picks which).  `opt` is a few bits
 * of the selector byte for the case's own choices. */
#ifndef FUZZ_PARSER_CHECKS_H
#define FUZZ_PARSER_CHECKS_H

#include <stddef.h>

/* csv.h: csv_parse_fields on the whole input as one row. */
void check_csv_row(const char *data, size_t size, unsigned opt);

/* stream.h: tse-kin's row loop (stream_rows) over the input as its stdin. */
void check_kin_stream(const char *data, size_t size, unsigned opt);

/* traj_file.h: traj_file_read of the input as a file. */
void check_traj_file(const char *data, size_t size, unsigned opt);

/* kin_params_file.h: tse-kin's kin_params_parse_stream of the input. */
void check_kin_params(const char *data, size_t size, unsigned opt);

/* param_text.h: the controller's SI parameter file, param_file_read of the input as a file. */
void check_param_file(const char *data, size_t size, unsigned opt);

/* The input as a file that fopen can open, without writing to a disk: a memfd, reused by every
 * call; returns its path ("/proc/self/fd/N"). */
const char *mem_file(const char *data, size_t size);

/* Runs fn(arg) with stderr sent to /dev/null: parsers that report on stderr would otherwise flood
 * the fuzzer's log.  A broken invariant is only reported after stderr is back. */
void without_stderr(void (*fn)(void *), void *arg);

/* err[0..cap) after a refusal: a message that is NUL-terminated inside the buffer, not empty,
 * and starts with "NAME:"; returns the line it names ("NAME:LINE: ..."), or 0 for "NAME: ...". */
int message_line(const char *err, size_t cap, const char *name);

#endif
