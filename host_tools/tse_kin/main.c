/* tse-kin: offline kinematics and design analysis of a TSE (docs/kinematics.md).
 *
 * Promise: dispatch only.  `tse-kin COMMAND [options]`; --help anywhere prints the usage to stdout
 * and exits 0; a bad command line exits 2 with the reason on stderr; a parameter file that cannot
 * be read or is invalid (in the chosen precision) exits 1 naming the file and line.  Everything
 * else is the command's (commands.h). */
#include <stdio.h>
#include <string.h>

#include "commands.h"
#include "controller_set.h"
#include "tse_version.h"

enum { CONTROLLER_SET = 2 };

typedef struct {
    const char *name;
    const char *summary;
    unsigned options;
    int needs_design; /* whether main builds the design in the chosen precision; CONTROLLER_SET: the
                       * command reads --params as the controller's whole set (controller_set.h) */
    int (*run)(const kin_run *run);
    const char *help;
    int (*check)(const kin_options *o, char *err, size_t errlen); /* NULL: options.c's checks suffice */
} command;

static const command commands[] = {
    {"ik", "poses -> status,scissor,s_a1,s_b1,s_a2,s_b2,s_a3,s_b3 (stdin to stdout)",
     KIN_OPT_PARAMS | KIN_OPT_PRECISION, 1, cmd_ik, cmd_ik_help, NULL},
    {"fk", "slides [+ seed pose] -> status,scissor,x,y,z,roll,pitch,yaw", KIN_OPT_PARAMS | KIN_OPT_PRECISION, 1,
     cmd_fk, cmd_fk_help, NULL},
    {"jacobian", "poses -> status,scissor, dq/dp (36), singular values of dp/dq (6)",
     KIN_OPT_PARAMS | KIN_OPT_PRECISION, 1, cmd_jacobian, cmd_jacobian_help, NULL},
    {"haf", "vertical gear ratio sigma_z and the Height Amplification Factor",
     KIN_OPT_PARAMS | KIN_OPT_PRECISION | KIN_OPT_Z, 1, cmd_haf, cmd_haf_help, NULL},
    {"workspace", "reachable fraction of the paper's cylindrical grid",
     KIN_OPT_PARAMS | KIN_OPT_PRECISION | KIN_OPT_GRID | KIN_OPT_ORIENTATION | KIN_OPT_POINTS, 1, cmd_workspace,
     cmd_workspace_help, NULL},
    {"bench", "timing of inverse and forward kinematics, double and float; bench plan: of the planner",
     KIN_OPT_ARGS | KIN_OPT_PARAMS | KIN_OPT_N, 0, cmd_bench, cmd_bench_help, cmd_bench_check},
    {"params", "a parameter file of the defaults, every key with its unit and rule", 0, 0, cmd_params,
     cmd_params_help, NULL},
    {"sweep", "PARAM FROM TO N: HAF and workspace of N designs (the paper's design study)",
     KIN_OPT_ARGS | KIN_OPT_PARAMS | KIN_OPT_PRECISION | KIN_OPT_GRID | KIN_OPT_JOBS, 1, cmd_sweep,
     cmd_sweep_help, cmd_sweep_check},
    {"profile", "singular values, sigma_z and both margins along the vertical axis",
     KIN_OPT_PARAMS | KIN_OPT_PRECISION | KIN_OPT_Z | KIN_OPT_N, 1, cmd_profile, cmd_profile_help,
     cmd_profile_check},
    {"margins", "poses -> status,scissor,mu1,mu2,mu3,nu (where singularities lie)",
     KIN_OPT_PARAMS | KIN_OPT_PRECISION, 1, cmd_margins, cmd_margins_help, NULL},
    {"plan", "WAYPOINTS.csv -> a trajectory the controller accepts, near the fastest",
     KIN_OPT_ARGS | KIN_OPT_PARAMS | KIN_OPT_BLEND | KIN_OPT_PERIOD | KIN_OPT_JERK, CONTROLLER_SET, cmd_plan,
     cmd_plan_help,
     cmd_one_file_check},
    {"check", "TRAJ.csv judged by the controller's validator, offline", KIN_OPT_ARGS | KIN_OPT_PARAMS, CONTROLLER_SET,
     cmd_check, cmd_check_help, cmd_one_file_check},
};
enum { N_COMMANDS = (int)(sizeof commands / sizeof commands[0]) };

static void print_usage(FILE *f)
{
    fputs("usage: tse-kin COMMAND [options]\n"
          "       tse-kin COMMAND --help\n"
          "       tse-kin --version\n"
          "\n"
          "Offline kinematics of the Triple Scissor Extender (docs/kinematics.md). Units: metres, radians.\n"
          "\n"
          "commands:\n",
          f);
    for (int i = 0; i < N_COMMANDS; ++i)
        fprintf(f, "  %-10s %s\n", commands[i].name, commands[i].summary);
    fputs("\n"
          "options (which command takes which: see its --help):\n"
          "  --params FILE              design parameters (default: the paper's prototype)\n"
          "  --precision float|double   library build to use (default double)\n"
          "  --grid NR,NPHI,NZ          workspace grid (default 21,36,41; sweep 16,24,32)\n"
          "  --orientation R,P,Y        workspace orientation (default 0,0,0)\n"
          "  --z Z1,Z2,...              haf and profile heights (default 9, 60 inside the alpha stops)\n"
          "  --n N                      bench trajectory length (default 2000); profile heights (60)\n"
          "  --points                   workspace: the grid points, not their count\n"
          "  --jobs J                   sweep threads (default: the number of cores)\n"
          "  --blend M                  plan: cut corners by at most M metres (default 0: through each)\n"
          "  --period S                 plan: rows' spacing in seconds (default 0.02)\n"
          "  --jerk J|controller        plan: hold the slides' jerk to J m/s^3 (default: no limit)\n"
          "  --help                     usage, of the tool or of a command\n"
          "\n" KIN_HELP_ROWS "\n" KIN_HELP_PARAMS "\n" KIN_HELP_EXIT,
          f);
}

static int usage_error(const char *cmd, const char *msg)
{
    fprintf(stderr, "tse-kin: %s\n", msg);
    fprintf(stderr, "Try 'tse-kin %s--help'.\n", cmd ? cmd : "");
    return KIN_EXIT_USAGE;
}

static const command *find_command(const char *name)
{
    for (int i = 0; i < N_COMMANDS; ++i)
        if (!strcmp(commands[i].name, name))
            return &commands[i];
    return NULL;
}

static int is_help(const char *a)
{
    return !strcmp(a, "--help") || !strcmp(a, "-h");
}

static int run_command(const command *c, int argc, char **argv)
{
    char msg[512], cmd_prefix[32];
    snprintf(cmd_prefix, sizeof cmd_prefix, "%s ", c->name);
    kin_options opt;
    kin_options_default(&opt);
    if (kin_options_parse(argc, argv, c->options, &opt, msg, sizeof msg) != 0)
        return usage_error(cmd_prefix, msg);
    if (c->check && c->check(&opt, msg, sizeof msg) != 0)
        return usage_error(cmd_prefix, msg);

    kin_param_values params;
    kin_params_default(&params);
    const char *params_name = "the default parameters";
    if (opt.params_design && c->needs_design == CONTROLLER_SET)
        return usage_error(cmd_prefix, "--design: plans and trajectories are judged against a controller's set; "
                                       "give it as --params FILE");
    if (opt.params_path && c->needs_design != CONTROLLER_SET) {
        params_name = opt.params_path;
        if (kin_params_load(opt.params_path, opt.params_design ? KIN_PARAMS_DESIGN : KIN_PARAMS_CONTROLLER, &params,
                            msg, sizeof msg) != KIN_PARAMS_OK) {
            fprintf(stderr, "tse-kin: %s\n", msg);
            return KIN_EXIT_FILE;
        }
    }

    kin_run run = {&opt, &params, params_name, opt.use_float ? &kin_ops_float : &kin_ops_double, NULL};
    /* As long-lived as run.ctx: create() only writes it, but a checker that cannot see into
     * create() must assume the context keeps its address. */
    tse_param_id bad;
    if (c->needs_design == 1) {
        run.ctx = run.ops->create(&params, &bad);
        if (!run.ctx) {
            char note[64];
            snprintf(note, sizeof note, " in %s precision", run.ops->name);
            kin_params_describe_invalid(&params, bad, params_name, note, msg, sizeof msg);
            fprintf(stderr, "tse-kin: %s\n", msg);
            return KIN_EXIT_FILE;
        }
    }
    const int rc = c->run(&run);
    if (run.ctx)
        run.ops->destroy(run.ctx);
    return rc;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        print_usage(stderr);
        return KIN_EXIT_USAGE;
    }
    const char *name = argv[1];
    if (!strcmp(name, "--version")) {
        printf("tse-kin %s\n", TSE_VERSION);
        return KIN_EXIT_OK;
    }
    if (is_help(name) || !strcmp(name, "help")) {
        /* `tse-kin help ik` too, since people type it. */
        const command *c = argc > 2 && !strcmp(name, "help") ? find_command(argv[2]) : NULL;
        if (argc > 2 && !strcmp(name, "help") && !c) {
            char msg[256];
            snprintf(msg, sizeof msg, "unknown command '%.60s'", argv[2]);
            return usage_error(NULL, msg);
        }
        fputs(c ? c->help : "", stdout);
        if (!c)
            print_usage(stdout);
        return KIN_EXIT_OK;
    }
    const command *c = find_command(name);
    if (!c) {
        char msg[256];
        snprintf(msg, sizeof msg,
                 "unknown command '%.60s' (commands: ik, fk, jacobian, haf, workspace, bench, params, sweep, "
                 "profile, margins, plan, check)", name);
        return usage_error(NULL, msg);
    }
    /* --help wins over anything else on the line, even a mistake. */
    for (int i = 2; i < argc; ++i)
        if (is_help(argv[i])) {
            fputs(c->help, stdout);
            return KIN_EXIT_OK;
        }
    return run_command(c, argc - 2, argv + 2);
}
