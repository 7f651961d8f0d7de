/* The controller's parameters as people read and write them: SI text over the integer wire.
 *
 * The CAN wire and fw_param_table keep micro-units (um, urad, ppm, um/s, ...).  Here a name
 * without a unit suffix is SI: m, rad, m/s, m/s^2, m/s^3, rad/s, rad/s^2, a plain ratio for ppm,
 * 1/m, 1/s; names that carry their unit keep it (watchdog_ms in ms, step_pulse_ns in ns,
 * can_kbps in kbit/s).  Angles (the urad parameters eta, alpha_min, alpha_max) may also be
 * spelled NAME_deg, in degrees.  Nothing here changes a range: the table's integer limits are the
 * truth, shown in the unit of the spelling used.
 *
 * Host only (it uses stdio and the heap); the firmware never sees text. */
#ifndef PARAM_TEXT_H
#define PARAM_TEXT_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "fw/limits.h"
#include "fw/params.h"

typedef struct {
    int id;          /* fw_param_id */
    double per_unit; /* how many raw integer units one unit of this spelling is (1e6 for "m" of an
                      * "um" parameter, 1e6*pi/180 for "deg" of a "urad" one, 1 for "ms") */
    const char *unit;/* the unit of this spelling ("m", "rad", "deg", "m/s", "" for a ratio, "ms") */
} param_key;

#define PARAM_PI 3.14159265358979323846

/* The suffix of an angle's spelling in degrees: eta_deg. */
#define PARAM_DEG_SUFFIX "_deg"

/* Looks a name up, case-insensitively: a table name (SI) or an angle's name + "_deg".
 * Returns 0, or -1 for an unknown name (k untouched). */
int param_lookup(const char *name, param_key *k);

/* The SI spelling of parameter id (table name, SI unit). */
void param_si_key(int id, param_key *k);

/* Converts the text of a value in k's unit into the wire integer, rounding to the nearest
 * integer (halves away from zero); surrounding blanks are allowed.  Refuses (returns -1, *raw
 * untouched) text that is not one finite number, or a value outside the table's range (or a
 * can_kbps other than the four rates), with a message naming the parameter, the value, the unit
 * and the range in k's unit, e.g. "slide_vmax = 3 m/s is outside 0.001..2 m/s". */
int param_from_text(const param_key *k, const char *text, int32_t *raw, char *err, size_t errlen);

/* param_from_text's number rule alone, for a reader that judges no range (param_text_scan): 0,
 * or -1 with "NAME: 'TEXT' is not one finite number (in UNIT)". */
int param_number_from_text(const param_key *k, const char *text, char *err, size_t errlen);

/* Writes raw in k's unit, exactly where the integer allows ("0.15" for 150000 um/s, "1.727" for
 * 1727000 um); in a unit that is not a power of ten of the raw one (degrees), the fewest digits
 * that param_from_text turns back into raw.  Returns buf. */
const char *param_to_text(const param_key *k, int32_t raw, char *buf, size_t cap);

/* Explains why a controller running at `rates` (its INFO's; FW_RATES_BUILT_IN for the built-in
 * ones) refuses set s (fw_params_judge_config), in words with the rule and the values in SI, e.g. "alpha_min = 1.3 rad must be
 * below alpha_max = 1.2 rad" or "home_sw_3 = 0.05 m: the six homing switches cannot be reached
 * together (...)".  For a set it accepts, says so. */
void param_explain_invalid(const fw_param_set *s, fw_rates rates, char *err, size_t errlen);

/* The same for a refusal already known: rule f.rule, about parameter f.id (-1: none), in set s, by a
 * controller at `rates`.
 * A refusal's rule comes from the controller (REJECT's where), its parameter from the command:
 * where s breaks the same rule by fw_params_judge_config the parameter that judge blames is named
 * (a switch pair's first switch), otherwise f.id.  Never says the set is valid (rule
 * FW_RULE_NONE says the refusal gave no rule). */
void param_explain_fault(const fw_param_set *s, fw_param_fault f, fw_rates rates, char *err, size_t errlen);

/* The slide speed limit in effect for set s at the controller's rates (fw_speed_limit_from_params)
 * and what sets it, e.g. "slide speed limit in effect: 0.1392 m/s, set by the step generator: ...
 * (slide_vmax = 0.15 m/s is higher)"; for a set the step generator refuses, says so. */
const char *param_speed_limit_words(const fw_param_set *s, fw_rates rates, char *buf, size_t cap);

/* Whether parameter id takes part in the slide speed limit (slide_vmax, steps_per_m,
 * step_rate_max, dir_setup_ns). */
int param_sets_speed_limit(int id);

/* Parameter text files: `key = value` lines, '#' comments (also after a value), blank lines, CRLF,
 * an optional UTF-8 BOM; keys as param_lookup takes them; missing keys keep *s's value (start from
 * fw_params_default for a fresh set).  A line that is not `key = value`, a key given twice (also
 * under its other spelling), an unknown key, a bad value, or a whole set that fw_params_check
 * refuses is an error "PATH:LINE: ..." (for the set, the line of the key fw_params_check blames;
 * when the file does not set that key, the message says its kept value is what is in conflict).
 * An unreadable file is "PATH: ...".  The set is judged at `rates`, the rates of the controller
 * that is to run it.  Returns 0, or -1 with *s unchanged. */
int param_file_read(const char *path, fw_param_set *s, fw_rates rates, char *err, size_t errlen);

/* What a parameter file said, beside the set it gives: the one reader's whole answer, for the
 * tools that compute with the values as written (tse-kin, tse.kin.Params) rather than with the
 * wire's integers.  A file's value is within its parameter's range as written (param_from_text),
 * so the written values keep every rule that the integers keep. */
typedef struct {
    fw_param_set set;     /* what the controller takes (the integers) */
    double si[FP_COUNT];  /* each value as the file wrote it, in SI (an angle in _deg in radians);
                           * a parameter the file does not set: its integer in SI */
    int line[FP_COUNT];   /* the line that set it; 0: not in the file */
    int degrees[FP_COUNT];/* set through its _deg spelling */
    fw_rates rates;       /* the rates the whole set is judged at (the controller's that is to run
                           * it); param_reading_start: the built-in ones */
} param_reading;

/* A reading of no file over set base: no lines, base's values, the built-in rates. */
void param_reading_start(param_reading *r, const fw_param_set *base);

/* param_file_read's rules over `text` (modified in place; NUL-terminated), `name` naming it in
 * messages, over r->set, the set judged at r->rates (r from param_reading_start); on success *r is
 * the whole reading, else -1 with *r unchanged. */
int param_text_read(char *text, const char *name, param_reading *r, char *err, size_t errlen);

/* The same for the file at path (param_file_read's limits); -2 (not -1) for a file that cannot be
 * opened or read. */
int param_file_read_full(const char *path, param_reading *r, char *err, size_t errlen);

/* The reader's rules for a design rather than a controller (tse-kin --design): the same lines,
 * keys, case, numbers and duplicates, but no value is held to the controller's ranges and the set
 * to none of its rules (the caller judges the design by its own).  r->si has the values; r->set
 * is left as it was. */
int param_text_scan(char *text, const char *name, param_reading *r, char *err, size_t errlen);
int param_file_scan(const char *path, param_reading *r, char *err, size_t errlen);

/* Writes set s to PATH through PATH.tmp, fsynced and renamed over PATH (keeping PATH's
 * permissions): never a half-written file.
 * - No file at PATH (or not a regular file): every parameter in SI, each after a comment with its
 *   doc, unit, range and default (the template).
 * - A parameter file: the user's file with only the values changed.  Every line is kept as it was
 *   (comments, blank lines, order, line ends, a BOM, each key in the spelling and case it was
 *   written, degrees for a _deg key) except the value of a line that reads back to another value
 *   than s's, which is rewritten in that line's unit; the parameters the file does not set whose
 *   value in s is not the default are appended under a comment, one 'name = value  # unit' line
 *   each.  Reading the result gives s.  A file param_file_read refuses is not written over (its
 *   message says why).
 * A set that a controller at `rates` refuses (param_explain_invalid) is not written (param_file_read
 * at those rates would refuse the file).  Returns 0, or -1 with err (PATH untouched). */
int param_file_write(const char *path, const fw_param_set *s, fw_rates rates, char *err, size_t errlen);

/* One line of a parameter file for parameter id of s: "name = value   # unit" (a ratio's
 * comment says "ratio"), in SI: what tse-sim's and tse-kin's readers take back. */
void param_file_line(FILE *f, const fw_param_set *s, int id);

/* The whole set as a parameter file, one param_file_line each, after `title` (a comment, may be
 * NULL) and a comment with the slide speed limit in effect at `rates`: what `tsectl params dump`
 * prints. */
void param_file_dump(FILE *f, const fw_param_set *s, fw_rates rates, const char *title);

#endif
