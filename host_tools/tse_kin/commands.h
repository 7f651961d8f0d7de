/* What main hands a command, what a command returns, and each command's entry and usage text.
 *
 * Promise of every command: it returns one of the KIN_EXIT_* codes and writes its results to
 * stdout, diagnostics to stderr. */
#ifndef TSE_KIN_COMMANDS_H
#define TSE_KIN_COMMANDS_H

#include "kin_ops.h"
#include "options.h"
#include "params_file.h"

/* The exit codes scripts rely on. */
enum {
    KIN_EXIT_OK = 0,    /* the input was read to its end (or the command finished) */
    KIN_EXIT_FILE = 1,  /* a file (parameters, stdin, stdout) could not be read, written or used */
    KIN_EXIT_USAGE = 2  /* bad command line */
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

extern const char cmd_ik_help[];
extern const char cmd_fk_help[];
extern const char cmd_jacobian_help[];
extern const char cmd_haf_help[];
extern const char cmd_workspace_help[];
extern const char cmd_bench_help[];

/* Shared paragraphs of the usage texts. */
#define KIN_HELP_PARAMS                                                                                      \
    "Parameter file (--params): 'key = value' lines, '#' starts a comment, blank lines allowed. Keys:\n"      \
    "L, k1, eta_deg, k3, k4, alpha_min_deg, alpha_max_deg, s_min, s_max, mu_min, nu_min (metres,\n"          \
    "degrees, ratios; see kinematics.md). Missing keys keep the prototype's values. An unknown or\n"          \
    "repeated key, a value that is not one finite number, or an invalid set is an error naming the\n"        \
    "file and line (exit 1).\n"

#define KIN_HELP_ROWS                                                                                        \
    "Input rows: comma-separated numbers, spaces around them allowed, LF or CRLF line ends. Every\n"          \
    "input line gives exactly one output line, in order. A malformed line (wrong number of fields,\n"        \
    "an empty field, a non-number, trailing text, a NUL byte, more than 4096 bytes) and a blank line\n"      \
    "give 'invalid,0' followed by nan for every number, and the stream goes on. Rows of numbers that\n"      \
    "are not finite (nan, inf) go to the library, which answers 'invalid' itself; so do numbers\n"       \
    "beyond the float range with --precision float, where they become inf. NaN is always written\n"      \
    "'nan'; other numbers are written with %.17g.\n"

#define KIN_HELP_EXIT "Exit status: 0 input read to its end, 1 unreadable or invalid file, 2 usage error.\n"

#endif
