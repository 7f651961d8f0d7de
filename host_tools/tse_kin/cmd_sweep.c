/* `tse-kin sweep`: the paper's design study, one parameter varied over a range of designs.
 *
 * Promise: '#' comment lines, then the header "param,value,haf,workspace,volume_m3", then one row
 * per design in the order of the values, whatever --jobs is: the figures are the ones `tse-kin haf`
 * (its summary's mean, at its default heights) and `tse-kin workspace --grid` (its fraction and
 * volume) print for that design, so a script may take either.  A design the library refuses keeps its row with
 * nan figures and a comment naming the parameter that is wrong; the sweep goes on.  The designs
 * run on --jobs threads (default: every core), with a progress bar on a terminal's stderr. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "commands.h"
#include "csv.h"
#include "haf_heights.h"
#include "parallel.h"
#include "text.h"

#define KIN_PI 3.14159265358979323846
/* More designs than a plot can show; the bound keeps a typo from running for a day. */
#define SWEEP_MAX_N 100000L

/* The paper's workspace grid (16 x 24 x 32 test points in r, phi, Z), the sweep's default. */
enum { SWEEP_GRID_R = 16, SWEEP_GRID_PHI = 24, SWEEP_GRID_Z = 32 };

const char cmd_sweep_help[] =
    "usage: tse-kin sweep PARAM FROM TO N [--grid NR,NPHI,NZ] [--params|--design FILE]\n"
    "                     [--precision float|double] [--jobs J]\n"
    "\n"
    "The paper's design study: N designs with the parameter-file key PARAM spaced evenly from FROM to\n"
    "TO inclusive (N = 1 takes FROM = TO), every other parameter from --params (default: the\n"
    "prototype). PARAM is any kinematic key of the parameter file, in its unit: k1, eta_deg (the\n"
    "paper's k2, degrees) or eta (radians), k3, k4, L, alpha_min(_deg), alpha_max(_deg), s_min,\n"
    "s_max, mu_min, nu_min. Prints '#' comment lines, then the header and one row per design:\n"
    "  param,value,haf,workspace,volume_m3\n"
    "param is PARAM, value its value (%.17g); haf the mean HAF over tse-kin haf's default heights\n"
    "(its summary line's mean for that design); workspace the reachable fraction of the cylindrical\n"
    "grid at zero orientation (tse-kin workspace's fraction, unrounded), on --grid (default the\n"
    "paper's 16,24,32); volume_m3 the reachable volume of the plate's centre summed from the same\n"
    "grid (tse-kin workspace's volume), the size that compares designs of different L. A comment\n"
    "names the paper's figures when the other parameters are its prototype's. A design the library refuses gives nan figures and a comment naming the\n"
    "parameter that is wrong; the sweep goes on. Rows come in the order of the values whatever\n"
    "--jobs is: the designs run on J threads (default: the number of cores), with a progress bar on\n"
    "stderr when it is a terminal and the sweep takes more than a second.\n"
    "\n" KIN_HELP_PARAMS "\n" KIN_HELP_EXIT;

typedef struct {
    const kin_param_key_def *key; /* the swept spelling */
    double from, to;
    long n;
} sweep_plan;

/* One design's figures, written by the one call that computes them. */
typedef struct {
    double value, haf, workspace, volume;
    tse_param_id bad; /* why the design was refused; TSE_PARAM_OK when it was not */
    int refused;
} sweep_row;

typedef struct {
    const kin_run *run;
    const sweep_plan *plan;
    const int *grid;
    sweep_row *rows;
} sweep_work;

static const kin_param_key_def *find_key(const char *name)
{
    const kin_param_key_def *keys;
    const int n = kin_param_keys(&keys);
    for (int i = 0; i < n; ++i)
        if (!strcasecmp(keys[i].key, name)) /* the parameter files' case rule (param_lookup) */
            return &keys[i];
    return NULL;
}

static int parse_plan(const kin_options *o, sweep_plan *plan, char *err, size_t errlen)
{
    if (o->n_args != 4) {
        snprintf(err, errlen, "sweep takes PARAM FROM TO N (4 arguments before or among the options); got %d",
                 o->n_args);
        return -1;
    }
    const char *name = o->args[0];
    plan->key = find_key(name);
    if (!plan->key) {
        const char *hint = !strcmp(name, "k2") ? " (the paper's k2 is eta: give eta_deg, or eta in radians)"
                           : kin_param_is_controller_only(name) ? " (a controller parameter: it does not change the "
                                                                  "kinematics)"
                                                                : "";
        snprintf(err, errlen,
                 "PARAM '%.60s' is not a kinematic key%s; keys: L, k1, eta, eta_deg, k3, k4, alpha_min, "
                 "alpha_min_deg, alpha_max, alpha_max_deg, s_min, s_max, mu_min, nu_min",
                 name, hint);
        return -1;
    }
    if (text_number(o->args[1], &plan->from) != 0) {
        snprintf(err, errlen, "FROM must be a finite number; got '%.60s'", o->args[1]);
        return -1;
    }
    if (text_number(o->args[2], &plan->to) != 0) {
        snprintf(err, errlen, "TO must be a finite number; got '%.60s'", o->args[2]);
        return -1;
    }
    /* Digits only: "10.0" or "1e1" designs is a slip worth a message. */
    const char *s = o->args[3];
    char *end = NULL;
    plan->n = s[0] >= '0' && s[0] <= '9' ? strtol(s, &end, 10) : 0;
    if (!end || *end != '\0' || plan->n < 1 || plan->n > SWEEP_MAX_N) {
        snprintf(err, errlen, "N must be a whole number of designs from 1 to %ld; got '%.60s'", SWEEP_MAX_N, s);
        return -1;
    }
    if (plan->n == 1 && plan->from != plan->to) {
        snprintf(err, errlen, "N = 1 is one design: FROM and TO must be equal; got %.17g and %.17g", plan->from,
                 plan->to);
        return -1;
    }
    return 0;
}

int cmd_sweep_check(const kin_options *o, char *err, size_t errlen)
{
    sweep_plan plan;
    return parse_plan(o, &plan, err, errlen);
}

static double value_at(const sweep_plan *plan, long i)
{
    /* The ends exactly as given: a sweep to 1 must reach k1 = 1, not 0.99999999999999989. */
    if (i == plan->n - 1)
        return plan->to;
    return plan->from + (plan->to - plan->from) * ((double)i / (double)(plan->n - 1));
}

static void sweep_one(void *ctx, long i)
{
    const sweep_work *w = ctx;
    const kin_run *run = w->run;
    sweep_row *row = &w->rows[i];
    row->value = value_at(w->plan, i);
    row->haf = row->workspace = row->volume = NAN;
    row->bad = TSE_PARAM_OK;
    row->refused = 0;

    kin_param_values p = *run->params;
    const kin_param_key_def *key = w->plan->key;
    p.v[key->id] = key->degrees ? row->value * (KIN_PI / 180.0) : row->value;
    kin_ctx *c = run->ops->create(&p, &row->bad);
    if (!c) {
        row->refused = 1;
        return;
    }
    double z[KIN_HAF_DEFAULT_HEIGHTS];
    const int nz = kin_haf_default_heights(&p, z);
    row->haf = kin_haf_mean(run->ops, c, z, nz, NULL);
    static const double level[3] = {0, 0, 0};
    long reachable = 0, total = 0;
    double volume = NAN;
    if (run->ops->workspace_volume(c, w->grid[0], w->grid[1], w->grid[2], level, &reachable, &total, &volume) ==
            TSE_OK &&
        total > 0) {
        row->workspace = (double)reachable / (double)total;
        row->volume = volume;
    }
    run->ops->destroy(c);
}

/* "k1 = 0 (needs 0 < k1 <= 1)": the refused parameter in the swept key's spelling when it is the
 * swept one (an angle swept in degrees is named in degrees), else in SI with degrees beside. */
static void describe_refusal(const kin_run *run, const sweep_plan *plan, const sweep_row *row, char *buf,
                             size_t len)
{
    if (row->bad == TSE_PARAM_OK) {
        snprintf(buf, len, "out of memory");
        return;
    }
    const int swept = row->bad == plan->key->id;
    const kin_param_key_def *keys, *k = NULL;
    const int n = kin_param_keys(&keys);
    for (int i = 0; i < n && !k; ++i)
        if (keys[i].id == row->bad && keys[i].degrees == (swept && plan->key->degrees))
            k = &keys[i];
    if (!k) {
        snprintf(buf, len, "not a valid design");
        return;
    }
    const double si = swept ? (plan->key->degrees ? row->value * (KIN_PI / 180.0) : row->value)
                            : run->params->v[row->bad];
    const double shown = k->degrees ? si * (180.0 / KIN_PI) : si;
    char deg[48] = "";
    if (!k->degrees && !strcmp(k->unit, "rad"))
        snprintf(deg, sizeof deg, " (%.9g deg)", si * (180.0 / KIN_PI));
    snprintf(buf, len, "not a valid design%s: %s = %.15g%s, needs %s",
             strcmp(run->ops->name, "float") ? "" : " in float precision", k->key, shown, deg, k->rule);
}

int cmd_sweep(const kin_run *run)
{
    char err[512];
    sweep_plan plan;
    if (parse_plan(run->opt, &plan, err, sizeof err) != 0) {
        /* main ran cmd_sweep_check first: this is a defect, not the user's slip. */
        fprintf(stderr, "tse-kin: %s\n", err);
        return KIN_EXIT_USAGE;
    }
    static const int paper_grid[3] = {SWEEP_GRID_R, SWEEP_GRID_PHI, SWEEP_GRID_Z};
    const int *grid = run->opt->grid_set ? run->opt->grid : paper_grid;
    const int jobs = run->opt->jobs > 0 ? run->opt->jobs : kin_default_jobs();

    sweep_row *rows = calloc((size_t)plan.n, sizeof *rows);
    if (!rows) {
        fprintf(stderr, "tse-kin: out of memory for %ld designs\n", plan.n);
        return KIN_EXIT_FILE;
    }
    sweep_work w = {run, &plan, grid, rows};
    char what[64];
    snprintf(what, sizeof what, "sweep %s", plan.key->key);
    kin_progress bar;
    kin_progress_start(&bar, what, plan.n);
    kin_parallel_for(plan.n, jobs, sweep_one, &w, &bar);
    kin_progress_end(&bar);

    printf("# sweep of %s from %.17g to %.17g, %ld designs; every other parameter from %s\n", plan.key->key, plan.from,
           plan.to, plan.n, run->params_name);
    printf("# haf: mean HAF over tse-kin haf's default heights (%d, 5 %% inside the alpha stops); "
           "workspace: reachable fraction of the %d x %d x %d grid (r, phi, Z) at zero orientation; volume_m3: "
           "the reachable volume of the plate's centre, the sum of those points' cells (tse-kin workspace)\n",
           KIN_HAF_DEFAULT_HEIGHTS, grid[0], grid[1], grid[2]);
    printf("# precision %s; %d thread%s%s\n", run->ops->name, jobs, jobs == 1 ? "" : "s",
           kin_params_is_prototype(run->params)
               ? " (paper, prototype: HAF " KIN_PAPER_HAF ", workspace " KIN_PAPER_WORKSPACE ")"
               : "");
    for (long i = 0; i < plan.n; ++i) {
        if (!rows[i].refused)
            continue;
        char why[256];
        describe_refusal(run, &plan, &rows[i], why, sizeof why);
        printf("# %s = %.17g: %s; its figures are nan\n", plan.key->key, rows[i].value, why);
    }
    printf("param,value,haf,workspace,volume_m3\n");
    for (long i = 0; i < plan.n; ++i) {
        fputs(plan.key->key, stdout);
        csv_put_numbers(stdout, (const double[4]){rows[i].value, rows[i].haf, rows[i].workspace, rows[i].volume}, 4);
        putchar('\n');
    }
    free(rows);
    if (fflush(stdout) != 0 || ferror(stdout)) {
        fprintf(stderr, "tse-kin: error writing the output\n");
        return KIN_EXIT_FILE;
    }
    return KIN_EXIT_OK;
}
