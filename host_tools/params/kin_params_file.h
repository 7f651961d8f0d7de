/* The kinematic parameters of a parameter file, for tse-kin and tse.kin.Params.
 *
 * Promise: a parameter file is read by the one reader every tool uses (param_text.h: the same
 * lines, comments, keys in any case, _deg angles, number rule and duplicates as tse-sim and
 * tsectl), judged in one of two ways:
 * - as a controller's set (KIN_PARAMS_CONTROLLER, tse-kin --params, Params.from_file): by the
 *   controller's ranges and rules of the whole set (param_file_read), so exactly the files tse-sim
 *   accepts are accepted, with the same messages;
 * - as a design (KIN_PARAMS_DESIGN, tse-kin --design, Params.from_file(design=True)): by
 *   kinematics.md's rules for a valid set only (tse_params_check), so that designs no controller
 *   is configured for (L = 1e39, a rigid scissor without homing switches set) can be analysed; the
 *   controller's other keys are then only checked to be numbers.
 * What tse-kin computes with are the kinematic values as the file wrote them, in double (an angle
 * given in degrees converted once), not the wire's micro-unit integers; the values the file does
 * not set keep the ones given (normally the prototype's, tse_params_default, unrounded).  A
 * controller's set's written values keep every rule of tse_params_check that its integers keep
 * (each is within its parameter's range as written, and rounding keeps order). */
#ifndef TSE_KIN_PARAMS_FILE_H
#define TSE_KIN_PARAMS_FILE_H

#include <stddef.h>
#include <stdio.h>

#include "tse/params.h"

/* Parameters in SI units and radians, indexed by tse_param_id (index 0 unused), with where each
 * came from: the precision-neutral form that both library builds are fed from. */
typedef struct {
    double v[TSE_PARAM_COUNT];
    int line[TSE_PARAM_COUNT];    /* line of the file that set the value; 0 for a default */
    int degrees[TSE_PARAM_COUNT]; /* set through its _deg spelling: messages speak degrees */
} kin_param_values;

/* How a file is judged (see above). */
typedef enum { KIN_PARAMS_CONTROLLER = 0, KIN_PARAMS_DESIGN = 1 } kin_params_judge;

/* Outcome of loading a file; the values are tse-kin's exit codes' reasons. */
typedef enum {
    KIN_PARAMS_OK = 0,
    KIN_PARAMS_BAD = -1,       /* read, but not a valid parameter file */
    KIN_PARAMS_UNREADABLE = -2 /* cannot be opened or read */
} kin_params_outcome;

/* One spelling of a kinematic key, for the template, tse-kin sweep, tse.kin.Params and the tests:
 * its name is the library's (TSE_PARAM_NAME_*), with PARAM_DEG_SUFFIX for degrees.  The fields in the order a
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

/* The kinematic spellings, each SI one followed by its degrees one, in the order of tse_param_id;
 * returns how many. */
int kin_param_keys(const kin_param_key_def **keys);

/* The values as the double build's tse_params. */
void kin_params_to_tse(const kin_param_values *p, tse_params *t);

/* The prototype's values (tse_params_default of the double build), no line. */
void kin_params_default(kin_param_values *p);

/* Whether every kinematic value is the prototype's (to 1e-12 relative, so that eta_deg = 30 is
 * the default eta): only then does a command print the paper's figures beside its own. */
int kin_params_is_prototype(const kin_param_values *p);

/* Reads the text of a parameter file over the values already in *p (normally the defaults; the
 * controller's other parameters over theirs), judged as `judge` says.  `name` is the file name
 * used in messages.  Returns KIN_PARAMS_OK, or KIN_PARAMS_BAD with *p untouched and the message
 * in err. */
kin_params_outcome kin_params_parse(const char *text, const char *name, kin_params_judge judge, kin_param_values *p,
                                    char *err, size_t errlen);

/* The same from the file at path; KIN_PARAMS_UNREADABLE when it cannot be opened or read. */
kin_params_outcome kin_params_load(const char *path, kin_params_judge judge, kin_param_values *p, char *err,
                                   size_t errlen);

/* Message for a set that a library build rejected with `bad` (tse_geometry_init's answer): names
 * the line that set that key (in the spelling the file used), or says it is the default value.
 * `name` is the file name (or a description when there is no file); `context` is appended to the
 * complaint, e.g. " in float precision", or "". */
void kin_params_describe_invalid(const kin_param_values *p, tse_param_id bad, const char *name,
                                 const char *context, char *err, size_t errlen);

/* The SI key of a parameter: tse_param_name ("eta"); "?" if none. */
const char *kin_param_key(tse_param_id id);

/* Whether name (in any case) is one of the controller's parameters that are not kinematic. */
int kin_param_is_controller_only(const char *name);

#endif
