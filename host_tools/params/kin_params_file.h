/* The parameter file of tse-kin.
 *
 * Promise: `key = value` lines; `#` starts a comment (whole line or trailing); blank lines, CRLF
 * and a UTF-8 BOM at the start are fine.  Names follow the controller's parameter table
 * (fw_param_table, firmware/include/fw/params.h): a name without a unit suffix is in SI (m, rad,
 * m/s, plain ratios), a name with one carries its unit.  The kinematic keys are L, k1, eta, k3,
 * k4, alpha_min, alpha_max, s_min, s_max, mu_min, nu_min; the three angles may instead be given
 * in degrees as eta_deg, alpha_min_deg, alpha_max_deg.  The controller's other names (slide_vmax,
 * watchdog_ms, ..., can_kbps, in SI or their suffix's unit) are accepted, checked to be one finite
 * number and ignored, so that one file serves tse-kin and the simulator.  Keys are case-sensitive.
 * Missing keys keep the prototype's values (tse_params_default).
 *
 * An unknown key, a key given twice (also under its other spelling: both lines are named), a value
 * that is not one finite number, or a set the library rejects is an error whose message names the
 * file and the line (or "default value" for a key the file did not set).  Nothing is applied from
 * a refused file.  No I/O other than the FILE* given. */
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
    int line[TSE_PARAM_COUNT];    /* line of the file that set the value; 0 for a default */
    int degrees[TSE_PARAM_COUNT]; /* set through its _deg spelling: messages speak degrees */
} kin_param_values;

/* Outcome of loading a file; the values are tse-kin's exit codes' reasons. */
typedef enum {
    KIN_PARAMS_OK = 0,
    KIN_PARAMS_BAD = -1,       /* read, but not a valid parameter file */
    KIN_PARAMS_UNREADABLE = -2 /* cannot be opened or read */
} kin_params_outcome;

/* One spelling of a kinematic key, for the template and the tests.  The fields in the order a
 * row of the table reads, not the tightest (8 bytes a row of a 16-row table).
 * NOLINTNEXTLINE(clang-analyzer-optin.performance.Padding) */
typedef struct {
    tse_param_id id;
    const char *key;  /* "eta", "eta_deg", ... */
    int degrees;      /* the value is in degrees */
    const char *unit; /* of the value: "m", "rad", "deg", or "" for a ratio */
    const char *rule; /* docs/kinematics.md, "Valid parameter sets", in this spelling's unit */
    const char *doc;
} kin_param_key_def;

/* The kinematic spellings, SI before degrees, in the order of tse_param_id; returns how many. */
int kin_param_keys(const kin_param_key_def **keys);

/* The prototype's values (tse_params_default of the double build), no line. */
void kin_params_default(kin_param_values *p);

/* Whether every kinematic value is the prototype's (to 1e-12 relative, so that eta_deg = 30 is
 * the default eta): only then does a command print the paper's figures beside its own. */
int kin_params_is_prototype(const kin_param_values *p);

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
 * the line that set that key (in the spelling the file used), or says it is the default value.
 * `name` is the file name (or a description when there is no file); `context` is appended to the
 * complaint, e.g. " in float precision", or "". */
void kin_params_describe_invalid(const kin_param_values *p, tse_param_id bad, const char *name,
                                 const char *context, char *err, size_t errlen);

/* The SI key of a parameter: tse_param_name ("eta"); "?" if none. */
const char *kin_param_key(tse_param_id id);

/* Whether name is one of the controller's parameters that tse-kin accepts and ignores. */
int kin_param_is_controller_only(const char *name);

#endif
