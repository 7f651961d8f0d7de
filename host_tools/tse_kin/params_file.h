/* The parameter file of tse-kin.
 *
 * Promise: `key = value` lines with the keys L, k1, eta_deg, k3, k4, alpha_min_deg, alpha_max_deg,
 * s_min, s_max, mu_min, nu_min; `#` starts a comment (whole line or trailing); blank lines and CRLF
 * are fine.  Missing keys keep the prototype's values (tse_params_default).  Angles are degrees in
 * the file and radians in kin_param_values.  An unknown key, a repeated key, a value that is not
 * one finite number, or a set the library rejects is an error whose message names the file and the
 * line (or "default value" for a key the file did not set).  No I/O other than the FILE* given. */
#ifndef TSE_KIN_PARAMS_FILE_H
#define TSE_KIN_PARAMS_FILE_H

#include <stddef.h>
#include <stdio.h>

#include "tse/params.h"

/* Longest parameter file accepted, and longest line in it. */
#define KIN_PARAMS_MAX_BYTES 65536
#define KIN_PARAMS_MAX_LINE 512

/* Parameters in SI units and radians, indexed by tse_param_id (index 0 unused), with where each
 * came from: the precision-neutral form that both library builds are fed from. */
typedef struct {
    double v[TSE_PARAM_COUNT];
    int line[TSE_PARAM_COUNT]; /* line of the file that set the value; 0 for a default */
} kin_param_values;

/* Outcome of loading a file; the values are tse-kin's exit codes' reasons. */
typedef enum {
    KIN_PARAMS_OK = 0,
    KIN_PARAMS_BAD = -1,       /* read, but not a valid parameter file */
    KIN_PARAMS_UNREADABLE = -2 /* cannot be opened or read */
} kin_params_outcome;

/* The prototype's values (tse_params_default of the double build), no line. */
void kin_params_default(kin_param_values *p);

/* Parses the text of a parameter file over the values already in *p (normally the defaults), then
 * validates the whole set with tse_params_check.  `name` is the file name used in messages.
 * Returns KIN_PARAMS_OK, or KIN_PARAMS_BAD with *p untouched and the message in err. */
kin_params_outcome kin_params_parse(const char *text, const char *name, kin_param_values *p, char *err,
                                    size_t errlen);

/* The same from an open stream (read to its end, at most KIN_PARAMS_MAX_BYTES). */
kin_params_outcome kin_params_parse_stream(FILE *f, const char *name, kin_param_values *p, char *err,
                                           size_t errlen);

/* Opens and parses a file; KIN_PARAMS_UNREADABLE when it cannot be opened or read. */
kin_params_outcome kin_params_load(const char *path, kin_param_values *p, char *err, size_t errlen);

/* Message for a set that a library build rejected with `bad` (tse_geometry_init's answer): names
 * the line that set that key, or says it is the default value.  `name` is the file name (or a
 * description when there is no file); `context` is appended to the complaint, e.g. " in float
 * precision", or "". */
void kin_params_describe_invalid(const kin_param_values *p, tse_param_id bad, const char *name,
                                 const char *context, char *err, size_t errlen);

/* The file's key of a parameter: tse_param_name with "_deg" for angles ("eta_deg"); "?" if none. */
const char *kin_param_key(tse_param_id id);

#endif
