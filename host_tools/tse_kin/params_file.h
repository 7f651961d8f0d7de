/* The parameter file of tse-kin: `key = value` lines, `#` comments, keys of kinematics.md with
 * angles in degrees.  Missing keys keep the prototype's values.  Every error names the line. */
#ifndef TSE_KIN_PARAMS_FILE_H
#define TSE_KIN_PARAMS_FILE_H

#include <stddef.h>
#include <stdio.h>

#include "tse/params.h"

/* Parameters in SI units and radians, in the order of tse_param_id (index 0 unused). */
typedef struct {
    double v[TSE_PARAM_COUNT];
    int line[TSE_PARAM_COUNT]; /* line that set each value, 0 for a default */
} kin_param_values;

/* The prototype's values (kinematics.md). */
void kin_params_default(kin_param_values *p);

/* Parses the text of a parameter file.  Returns 0, or -1 with a message naming `name` and the
 * line in err.  On error *p is left as it was. */
int kin_params_parse(const char *text, const char *name, kin_param_values *p, char *err, size_t errlen);

/* Reads and parses a file.  Returns 0, -1 for bad content, -2 when it cannot be read. */
int kin_params_load(const char *path, kin_param_values *p, char *err, size_t errlen);

/* The user-facing key of a parameter ("eta_deg" for eta, ...). */
const char *kin_param_key(tse_param_id id);

#endif
