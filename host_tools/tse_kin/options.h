/* Command-line options of tse-kin's commands.
 *
 * Promise: an option a command does not take, an option without its value, or a value that is not
 * exactly what the option needs is refused with a message naming it (the caller exits 2).  Options
 * may be written `--name VALUE` or `--name=VALUE`; when one is repeated the last one counts.
 * Pure: no I/O. */
#ifndef TSE_KIN_OPTIONS_H
#define TSE_KIN_OPTIONS_H

#include <stddef.h>

/* Which options a command takes (a bit set). */
enum {
    KIN_OPT_PARAMS = 1u << 0,      /* --params FILE or --design FILE */
    KIN_OPT_PRECISION = 1u << 1,   /* --precision float|double */
    KIN_OPT_GRID = 1u << 2,        /* --grid NR,NPHI,NZ */
    KIN_OPT_ORIENTATION = 1u << 3, /* --orientation R,P,Y */
    KIN_OPT_Z = 1u << 4,           /* --z Z1,Z2,... */
    KIN_OPT_N = 1u << 5,           /* --n N */
    KIN_OPT_POINTS = 1u << 6,      /* --points (a switch: no value) */
    KIN_OPT_JOBS = 1u << 7,        /* --jobs J */
    KIN_OPT_ARGS = 1u << 8,        /* positional arguments: anything not starting with "--" */
    KIN_OPT_BLEND = 1u << 9,       /* --blend M */
    KIN_OPT_PERIOD = 1u << 10,     /* --period S */
    KIN_OPT_JERK = 1u << 11        /* --jerk J|controller */
};

#define KIN_MAX_Z 256
/* Bounds of --grid (each count, and the product) and of --n: beyond them a run takes hours. */
#define KIN_GRID_MAX_AXIS 100000L
#define KIN_GRID_MAX_POINTS 100000000L
#define KIN_BENCH_MAX_N 10000000L
/* Positional arguments a command may take (sweep's PARAM FROM TO N), and threads of --jobs. */
#define KIN_MAX_ARGS 4
#define KIN_MAX_JOBS 256

#define KIN_DEFAULT_GRID_R 21
#define KIN_DEFAULT_GRID_PHI 36
#define KIN_DEFAULT_GRID_Z 41
#define KIN_DEFAULT_BENCH_N 2000
/* --blend and --period: plan's ranges (planner/include/plan/plan.h says why). */
#define KIN_BLEND_MAX 1.0
#define KIN_PERIOD_MIN 0.001
#define KIN_PERIOD_MAX 1.0

typedef struct {
    const char *params_path;  /* NULL: the prototype's parameters */
    int params_design;        /* given as --design: judged as a design (kin_params_file.h) */
    int use_float;            /* --precision float */
    int grid[3];              /* n_r, n_phi, n_z */
    double orientation[3];    /* roll, pitch, yaw [rad] */
    double z[KIN_MAX_Z];      /* --z heights [m] */
    int n_z;                  /* 0: the command's default heights */
    long bench_n;             /* poses of the bench trajectory (and profile's heights) */
    int grid_set, n_set;      /* --grid, --n given (commands with other defaults than these) */
    int points;               /* --points */
    int jobs;                 /* --jobs; 0: the number of cores */
    double blend;             /* --blend [m]; 0: none */
    double period;            /* --period [s]; 0: the command's default */
    double jerk;              /* --jerk: plan_options.jmax (plan_jerk_from_text); 0: none */
    const char *args[KIN_MAX_ARGS]; /* positional arguments, in order */
    int n_args;
} kin_options;

void kin_options_default(kin_options *o);

/* Parses args[0..n) for a command that takes the options in `allowed`.  Returns 0, or -1 with the
 * reason in err.  --help is not an option here: the caller looks for it first.  With KIN_OPT_ARGS,
 * an argument that does not start with "--" is positional (so "-30" is a number, not an option),
 * at most KIN_MAX_ARGS of them; the command judges how many and what they say. */
int kin_options_parse(int n, char *const *args, unsigned allowed, kin_options *o, char *err, size_t errlen);

#endif
