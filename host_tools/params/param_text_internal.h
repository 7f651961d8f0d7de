/* What the parts of the parameter text library share: the words of a value and of a range. */
#ifndef PARAM_TEXT_INTERNAL_H
#define PARAM_TEXT_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "param_text.h"

/* "0.15 m/s", "0.2647" (a ratio has no unit), "30 deg". */
const char *param_value_words(const param_key *k, int32_t raw, char *buf, size_t cap);

/* Why a value (raw, the wire integer it came to, or beyond int32) that fw_param_value_ok refuses
 * is refused, in k's unit: "NAME = SHOWN UNIT is outside MIN..MAX UNIT", or, for a can_kbps
 * inside its range, the four rates.  shown is the value as its writer gave it. */
void param_range_error(const param_key *k, double raw, const char *shown, char *err, size_t errlen);

/* "name = value   # unit": param_file_line's text, without the line end. */
void param_line_text(const fw_param_set *s, int id, char *buf, size_t cap);

/* The whole file at path in a NUL-terminated buffer (the caller frees it), or NULL with
 * "PATH: why" in err: it cannot be read, is larger than 256 KiB or holds a NUL byte. */
char *param_file_text(const char *path, char *err, size_t errlen);

/* The text of the parameter file `text` with set s's values where they differ from what it says,
 * and the parameters it lacks appended (param_file_write's promise), in a buffer the caller frees;
 * NULL when out of memory.  `text` must read without error (param_file_read). */
char *param_file_merged(const char *text, const fw_param_set *s);

#endif
