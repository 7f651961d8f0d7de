/* What main hands a command, what a command returns, and each command's entry and usage text.
 *
 * Promise of every command: it returns one of the KIN_EXIT_* codes and writes its results to
 * stdout, diagnostics to stderr. */
#ifndef TSE_KIN_COMMANDS_H
#define TSE_KIN_COMMANDS_H

#include "kin_ops.h"
#include "options.h"
#include "kin_params_file.h"

/* The exit codes scripts rely on. */
enum {
    KIN_EXIT_OK = 0,    /* the input was read to its end (or the command finished) */
    KIN_EXIT_FILE = 1,  /* a file (parameters, stdin, stdout) could not be read, written or used */
    KIN_EXIT_USAGE = 2,  /* bad command line */
    KIN_EXIT_REFUSED = 3 /* plan, check: the path or the trajectory is refused (named on stderr) */
};

typedef struct {
    const kin_options *opt;
    const kin_param_values *params;
    const char *params_name; /* the file name, or a description of the defaults, for messages */
    const kin_ops *ops;      /* the precision chosen with --precision */
    kin_ctx *ctx;            /* the design in that precision */
} kin_run;

int cmd_ik(const kin_run *run);
int cmd_fk(const kin_run *run);
int cmd_jacobian(const kin_run *run);
int cmd_haf(const kin_run *run);
int cmd_workspace(const kin_run *run);
int cmd_bench(const kin_run *run);
int cmd_params(const kin_run *run);
int cmd_sweep(const kin_run *run);
int cmd_profile(const kin_run *run);
int cmd_margins(const kin_run *run);
int cmd_plan(const kin_run *run);
int cmd_check(const kin_run *run);
int cmd_bench_plan(const kin_run *run); /* bench plan */
/* workspace --points */
int cmd_workspace_points(const kin_run *run);
/* The '#' lines of both workspace forms: the grid, the orientation and how the volume is summed. */
void kin_workspace_comments(const kin_run *run);

/* The paper's figures for its prototype (docs/kinematics.md, "Forward kinematics, Jacobian,
 * metrics"), printed beside ours only when the design is the prototype (kin_params_is_prototype). */
#define KIN_PAPER_HAF "11.487"
#define KIN_PAPER_WORKSPACE "0.28"

/* Checks of a command's arguments that options.c cannot make alone (how many positional arguments
 * and what they say, options that exclude each other): 0, or -1 with the reason (exit 2).  main
 * calls them before it reads a parameter file. */
int cmd_sweep_check(const kin_options *o, char *err, size_t errlen);
int cmd_profile_check(const kin_options *o, char *err, size_t errlen);
int cmd_bench_check(const kin_options *o, char *err, size_t errlen);

extern const char cmd_ik_help[];
extern const char cmd_fk_help[];
extern const char cmd_jacobian_help[];
extern const char cmd_haf_help[];
extern const char cmd_workspace_help[];
extern const char cmd_bench_help[];
extern const char cmd_params_help[];
extern const char cmd_sweep_help[];
extern const char cmd_profile_help[];
extern const char cmd_margins_help[];
extern const char cmd_plan_help[];
extern const char cmd_check_help[];

/* Shared paragraphs of the usage texts. */
#define KIN_HELP_PARAMS                                                                                      \
    "Parameter file (--params FILE): the controller's parameter file, read as tse-sim and tsectl read\n"     \
    "it: 'key = value' lines, '#' starts a comment, blank lines and a UTF-8 BOM allowed; keys in any\n"      \
    "case; 'tse-kin params' prints one with every key. Kinematic keys: L, k1, eta, k3, k4,\n"               \
    "alpha_min, alpha_max, s_min, s_max, mu_min, nu_min in SI (metres, radians, ratios; see\n"              \
    "docs/kinematics.md), the angles also in degrees as eta_deg, alpha_min_deg, alpha_max_deg; the\n"       \
    "controller's others (slide_vmax, watchdog_ms, ...) as 'tsectl params list' gives them. Missing\n"      \
    "keys keep the prototype's values. An unknown or repeated key (also both spellings of an angle),\n"     \
    "a value that is not one finite number or outside the controller's range, or a set the\n"               \
    "controller refuses is an error naming the file and line (exit 1): tse-kin takes exactly the\n"         \
    "files tse-sim takes. --design FILE reads the same file as a design to analyse rather than a\n"        \
    "controller's set: only docs/kinematics.md's rules for a valid set hold (any L > 0, no homing\n"        \
    "switches needed), the controller's other keys only need to be numbers. Either way the\n"               \
    "kinematic values are used as written, in double.\n"

#define KIN_HELP_ROWS                                                                                        \
    "Input rows: comma-separated numbers, spaces around them allowed, LF or CRLF line ends, a UTF-8\n"       \
    "BOM at the start skipped. Every input line gives exactly one output line, in order. The first\n"        \
    "line may be a header (as many names as a row has numbers, e.g. x,y,z,roll,pitch,yaw): it is\n"          \
    "answered by the output's header. A malformed line (wrong number of fields, an empty field, a\n"         \
    "non-number, trailing text, a NUL byte, more than 4096 bytes) and a blank line give 'invalid,0'\n"       \
    "followed by nan for every number, and the stream goes on. Rows of numbers that are not finite\n"        \
    "(nan, inf) go to the library, which answers 'invalid' itself; so do numbers beyond the float\n"         \
    "range with --precision float, where they become inf. NaN is always written 'nan'; other numbers\n"      \
    "are written with %.17g.\n"

#define KIN_HELP_EXIT "Exit status: 0 input read to its end, 1 unreadable or invalid file, 2 usage error.\n"

#endif
