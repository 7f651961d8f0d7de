/* tse-kin: offline kinematics and design analysis of a TSE (kinematics.md).
 *
 * A contract scripts rely on: one output line per input line, numbers as %.17g, statuses by the
 * contract's names; exit 0 once the input is read to its end, 2 for a usage error, 1 for a file
 * that cannot be read or is not a valid parameter file. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "csv.h"
#include "kin_ops.h"
#include "params_file.h"
#include "tse/status.h"

#define EXIT_USAGE 2
#define EXIT_FILE 1
#define MAX_LINE 4096

typedef struct {
    const char *params_path;
    const kin_ops *ops;
    const char *grid;
    const char *orientation;
    const char *zs;
    long n;
} options;

static const char *const usage_main =
    "usage: tse-kin COMMAND [options]\n"
    "\n"
    "Offline kinematics of the Triple Scissor Extender (see kinematics.md).\n"
    "\n"
    "commands:\n"
    "  ik          poses on stdin -> status,scissor,s_a1,s_b1,s_a2,s_b2,s_a3,s_b3\n"
    "  fk          slides (and an optional seed pose) on stdin -> status,scissor,x,y,z,roll,pitch,yaw\n"
    "  jacobian    poses on stdin -> status,scissor, dq/dp (36, row-major), singular values of dp/dq (6)\n"
    "  haf         vertical gear ratio sigma_z and the Height Amplification Factor over Z\n"
    "  workspace   reachable fraction of the paper's cylindrical grid\n"
    "  bench       timing of the inverse and forward kinematics, float and double\n"
    "\n"
    "common options:\n"
    "  --params FILE              parameter file (key = value; see 'tse-kin ik --help')\n"
    "  --precision float|double   arithmetic of the library (default double)\n"
    "  --help                     this text, or a command's own\n"
    "\n"
    "exit status: 0 input read to its end, 1 unreadable or invalid file, 2 usage error\n";

static const char *const params_help =
    "parameter file: 'key = value' lines, '#' starts a comment; keys L, k1, eta_deg, k3, k4,\n"
    "alpha_min_deg, alpha_max_deg, s_min, s_max, mu_min, nu_min (SI units, angles in degrees);\n"
    "missing keys take the prototype's values. An unknown key, a repeated key, a malformed value\n"
    "or an invalid set is an error naming the line.\n";

static void print_help(const char *cmd)
{
    if (!cmd) {
        fputs(usage_main, stdout);
        return;
    }
    if (!strcmp(cmd, "ik"))
        printf("usage: tse-kin ik [--params FILE] [--precision float|double]\n\n"
               "Reads poses x,y,z,roll,pitch,yaw (metres, radians; R = Rz(yaw) Ry(pitch) Rx(roll)), one per\n"
               "line, and writes one line per input line: status,scissor,s_a1,s_b1,s_a2,s_b2,s_a3,s_b3\n"
               "(scissor 0 when ok, numbers %%.17g). Every line is solved from the home configuration, so\n"
               "the output does not depend on the order of the lines. A malformed line (or a blank one)\n"
               "gives 'invalid,0,nan,...' and the stream goes on.\n\n%s", params_help);
    else if (!strcmp(cmd, "fk"))
        printf("usage: tse-kin fk [--params FILE] [--precision float|double]\n\n"
               "Reads s_a1,s_b1,s_a2,s_b2,s_a3,s_b3 (metres), optionally followed by a seed pose (six more\n"
               "numbers; the home pose otherwise), and writes status,scissor,x,y,z,roll,pitch,yaw. The pose\n"
               "is checked by the inverse kinematics: a status other than ok means no pose is claimed.\n\n%s",
               params_help);
    else if (!strcmp(cmd, "jacobian"))
        printf("usage: tse-kin jacobian [--params FILE] [--precision float|double]\n\n"
               "Reads poses like 'ik' and writes, per line: status,scissor, then the 36 entries of dq/dp\n"
               "row by row (rows s_a1..s_b3; columns x,y,z,roll,pitch,yaw), then the 6 singular values\n"
               "of dp/dq, largest first.\n\n%s", params_help);
    else if (!strcmp(cmd, "haf"))
        printf("usage: tse-kin haf [--params FILE] [--precision float|double] [--z Z1,Z2,...]\n\n"
               "Prints z,sigma_z,sigma_z_k1_1,haf per height (default: 9 heights inside the alpha stops),\n"
               "where sigma_z = 1/(sqrt(6)|ds/dZ|) at X = Y = 0, zero orientation, and HAF divides it by\n"
               "the same design's with k1 = 1; then 'haf,mean,min,max,paper,11.487'.\n\n%s", params_help);
    else if (!strcmp(cmd, "workspace"))
        printf("usage: tse-kin workspace [--grid NR,NPHI,NZ] [--orientation R,P,Y] [--params FILE]\n"
               "                         [--precision float|double]\n\n"
               "Counts the reachable points of the grid r_i = (L/2) i/(NR-1), phi_j = 2 pi j/NPHI,\n"
               "Z_k = L k/(NZ-1) at a fixed orientation (radians; default 0,0,0). Default grid 21,36,41.\n"
               "The last line is reachable,total,fraction (the paper gives 0.28 for the prototype).\n\n%s",
               params_help);
    else if (!strcmp(cmd, "bench"))
        printf("usage: tse-kin bench [--params FILE] [--n N]\n\n"
               "Times the library on N poses (default 2000) of a smooth trajectory: median ns per 6-DOF\n"
               "inverse kinematics cold (from home) and warm (seeded with the previous solution), Newton\n"
               "iterations per pose (mean, max), and median ns per forward kinematics, for float and\n"
               "double. Also prints 'bench,KEY,VALUE' lines for scripts.\n\n%s", params_help);
}

static int usage_error(const char *fmt, const char *arg)
{
    fputs("tse-kin: ", stderr);
    fprintf(stderr, fmt, arg);
    fputs("\n(try 'tse-kin --help')\n", stderr);
    return EXIT_USAGE;
}

static void print_numbers(const double *v, int n)
{
    for (int k = 0; k < n; ++k)
        printf(",%.17g", v[k]);
}

static void print_nan(int n)
{
    for (int k = 0; k < n; ++k)
        fputs(",nan", stdout);
}

/* Reads stdin line by line; a line longer than MAX_LINE is one malformed row. */
static int next_line(char *buf, int *too_long)
{
    *too_long = 0;
    if (!fgets(buf, MAX_LINE, stdin))
        return 0;
    if (!strchr(buf, '\n') && !feof(stdin)) {
        int ch;
        while ((ch = getchar()) != EOF && ch != '\n')
            ;
        *too_long = 1;
    }
    return 1;
}

static int cmd_ik(const kin_ops *ops, kin_ctx *ctx, int jacobian)
{
    char line[MAX_LINE];
    int too_long;
    while (next_line(line, &too_long)) {
        double pose[6];
        const char *why = "";
        const int n = too_long ? -1 : csv_parse_row(line, pose, 6, &why);
        if (n != 6) {
            printf("invalid,0");
            print_nan(jacobian ? 42 : 6);
            putchar('\n');
            continue;
        }
        int scissor;
        if (jacobian) {
            double J[36], sv[6];
            const int st = ops->jacobian(ctx, pose, J, sv, &scissor);
            printf("%s,%d", tse_status_name((tse_status)st), scissor);
            if (st == TSE_OK) {
                print_numbers(J, 36);
                print_numbers(sv, 6);
            } else {
                print_nan(42);
            }
        } else {
            double q[6];
            const int st = ops->ik(ctx, pose, NULL, q, &scissor, NULL, NULL);
            printf("%s,%d", tse_status_name((tse_status)st), scissor);
            print_numbers(q, 6);
        }
        putchar('\n');
    }
    return ferror(stdin) ? EXIT_FILE : 0;
}

static int cmd_fk(const kin_ops *ops, kin_ctx *ctx)
{
    char line[MAX_LINE];
    int too_long;
    while (next_line(line, &too_long)) {
        double v[12];
        const char *why = "";
        const int n = too_long ? -1 : csv_parse_row(line, v, 12, &why);
        if (n != 6 && n != 12) {
            printf("invalid,0");
            print_nan(6);
            putchar('\n');
            continue;
        }
        double pose[6];
        int scissor;
        const int st = ops->fk(ctx, v, n == 12 ? v + 6 : NULL, pose, &scissor);
        printf("%s,%d", tse_status_name((tse_status)st), st == TSE_OK ? 0 : scissor);
        if (st == TSE_OK)
            print_numbers(pose, 6);
        else
            print_nan(6); /* never a wrong pose */
        putchar('\n');
    }
    return ferror(stdin) ? EXIT_FILE : 0;
}

static int parse_list(const char *s, double *out, int max)
{
    const char *why;
    return csv_parse_row(s, out, max, &why);
}

static int cmd_haf(const kin_ops *ops, kin_ctx *ctx, const kin_param_values *p, const char *zs)
{
    double z[64];
    int n = 0;
    if (zs) {
        n = parse_list(zs, z, 64);
        if (n <= 0)
            return usage_error("--z takes comma-separated heights, got '%s'", zs);
    } else {
        /* Nine heights inside the alpha stops, kept off the stops themselves. */
        const double L = p->v[TSE_PARAM_L];
        const double lo = L * sin(p->v[TSE_PARAM_ALPHA_MIN]), hi = L * sin(p->v[TSE_PARAM_ALPHA_MAX]);
        for (n = 0; n < 9; ++n)
            z[n] = lo + (hi - lo) * (0.05 + 0.9 * n / 8.0);
    }
    kin_param_values rigid = *p;
    rigid.v[TSE_PARAM_K1] = 1.0;
    kin_ctx *rctx = ops->create(&rigid);
    if (!rctx) {
        fprintf(stderr, "tse-kin: the design with k1 = 1 is not a valid parameter set\n");
        return EXIT_FILE;
    }
    printf("# z_m,sigma_z,sigma_z_k1_1,haf\n");
    double sum = 0, lo = INFINITY, hi = -INFINITY;
    int ok = 0;
    for (int i = 0; i < n; ++i) {
        double s, sr, h;
        const int st1 = ops->sigma_z(ctx, z[i], &s), st2 = ops->sigma_z(rctx, z[i], &sr), st3 = ops->haf(ctx, z[i], &h);
        if (st1 || st2 || st3) {
            printf("%.17g,nan,nan,nan\n", z[i]);
            continue;
        }
        printf("%.17g,%.17g,%.17g,%.17g\n", z[i], s, sr, h);
        sum += h;
        lo = h < lo ? h : lo;
        hi = h > hi ? h : hi;
        ++ok;
    }
    ops->destroy(rctx);
    if (ok == 0) {
        printf("haf,nan,nan,nan,paper,11.487\n");
        return 0;
    }
    printf("# HAF = sigma_z / sigma_z(k1 = 1): mean %.6f, min %.6f, max %.6f over %d heights; the paper gives 11.487\n",
           sum / ok, lo, hi, ok);
    printf("haf,%.17g,%.17g,%.17g,paper,11.487\n", sum / ok, lo, hi);
    return 0;
}

static int cmd_workspace(const kin_ops *ops, kin_ctx *ctx, const char *grid, const char *orientation)
{
    double g[3] = {21, 36, 41}, o[3] = {0, 0, 0};
    if (grid) {
        if (parse_list(grid, g, 3) != 3)
            return usage_error("--grid takes NR,NPHI,NZ, got '%s'", grid);
        for (int k = 0; k < 3; ++k)
            if (g[k] != floor(g[k]) || g[k] < (k == 1 ? 1 : 2) || g[k] > 100000)
                return usage_error("--grid needs whole numbers NR >= 2, NPHI >= 1, NZ >= 2, got '%s'", grid);
    }
    if (orientation) {
        if (parse_list(orientation, o, 3) != 3 || !isfinite(o[0]) || !isfinite(o[1]) || !isfinite(o[2]))
            return usage_error("--orientation takes three finite angles R,P,Y in radians, got '%s'", orientation);
    }
    long reach = 0, total = 0;
    ops->workspace(ctx, (int)g[0], (int)g[1], (int)g[2], o, &reach, &total);
    printf("# grid %d x %d x %d (r, phi, Z), orientation %g,%g,%g rad, precision %s\n", (int)g[0], (int)g[1],
           (int)g[2], o[0], o[1], o[2], ops->name);
    printf("# the paper gives 0.28 for the prototype\n");
    printf("%ld,%ld,%.6f\n", reach, total, total ? (double)reach / (double)total : 0.0);
    return 0;
}

/* The bench trajectory: a slow Lissajous through the workspace with small rotations, sampled
 * every 2 ms of its parameter; bench/fsolve_baseline.py uses the same definition. */
static void bench_trajectory(double (*p)[6], int n)
{
    for (int i = 0; i < n; ++i) {
        const double t = 0.002 * i;
        p[i][0] = 0.15 * sin(t);
        p[i][1] = 0.12 * sin(1.7 * t);
        p[i][2] = 1.0 + 0.3 * sin(0.5 * t);
        p[i][3] = 0.08 * sin(1.3 * t);
        p[i][4] = 0.06 * sin(0.9 * t);
        p[i][5] = 0.2 * sin(0.7 * t);
    }
}

static int cmd_bench(const kin_param_values *p, long n)
{
    double(*poses)[6] = malloc(sizeof(double[6]) * (size_t)n);
    if (!poses)
        return EXIT_FILE;
    bench_trajectory(poses, (int)n);
    const kin_ops *all[2] = {&kin_ops_double, &kin_ops_float};
    printf("# %ld poses of a Lissajous trajectory, 31 repeats, median of the per-pose means\n", n);
    for (int i = 0; i < 2; ++i) {
        kin_ctx *ctx = all[i]->create(p);
        if (!ctx) {
            free(poses);
            return EXIT_FILE;
        }
        kin_bench_result r;
        all[i]->bench(ctx, (const double(*)[6])poses, (int)n, 31, &r);
        all[i]->destroy(ctx);
        const char *nm = all[i]->name;
        printf("ik %-6s warm: median %8.1f ns/pose, Newton iterations mean %.2f max %d (3 scissors), fallbacks %ld\n",
               nm, r.ik_warm_ns, r.iter_warm_mean, r.iter_warm_max, r.fallbacks_warm);
        printf("ik %-6s cold: median %8.1f ns/pose, Newton iterations mean %.2f max %d (3 scissors), fallbacks %ld\n",
               nm, r.ik_cold_ns, r.iter_cold_mean, r.iter_cold_max, r.fallbacks_cold);
        printf("fk %-6s warm: median %8.1f ns/pose\n", nm, r.fk_ns);
        if (r.failures)
            printf("warning: %d poses of the trajectory were not ok in %s\n", r.failures, nm);
        printf("bench,ik_%s_warm_ns,%.1f\nbench,ik_%s_cold_ns,%.1f\nbench,fk_%s_ns,%.1f\n", nm, r.ik_warm_ns, nm,
               r.ik_cold_ns, nm, r.fk_ns);
        printf("bench,ik_%s_warm_iter_mean,%.3f\nbench,ik_%s_warm_iter_max,%d\n", nm, r.iter_warm_mean, nm,
               r.iter_warm_max);
    }
    free(poses);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc < 2)
        return usage_error("%s", "a command is needed");
    const char *cmd = argv[1];
    if (!strcmp(cmd, "--help") || !strcmp(cmd, "-h") || !strcmp(cmd, "help")) {
        print_help(NULL);
        return 0;
    }
    static const char *const commands[] = {"ik", "fk", "jacobian", "haf", "workspace", "bench"};
    int known = 0;
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; ++i)
        known |= !strcmp(cmd, commands[i]);
    if (!known)
        return usage_error("unknown command '%s'", cmd);

    options o = {NULL, &kin_ops_double, NULL, NULL, NULL, 2000};
    for (int i = 2; i < argc; ++i) {
        const char *a = argv[i];
        const int has_value = i + 1 < argc;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            print_help(cmd);
            return 0;
        } else if (!strcmp(a, "--params") && has_value) {
            o.params_path = argv[++i];
        } else if (!strcmp(a, "--precision") && has_value) {
            const char *v = argv[++i];
            if (!strcmp(v, "double"))
                o.ops = &kin_ops_double;
            else if (!strcmp(v, "float"))
                o.ops = &kin_ops_float;
            else
                return usage_error("--precision takes float or double, got '%s'", v);
        } else if (!strcmp(a, "--grid") && has_value && !strcmp(cmd, "workspace")) {
            o.grid = argv[++i];
        } else if (!strcmp(a, "--orientation") && has_value && !strcmp(cmd, "workspace")) {
            o.orientation = argv[++i];
        } else if (!strcmp(a, "--z") && has_value && !strcmp(cmd, "haf")) {
            o.zs = argv[++i];
        } else if (!strcmp(a, "--n") && has_value && !strcmp(cmd, "bench")) {
            char *end;
            o.n = strtol(argv[++i], &end, 10);
            if (*end || o.n < 2 || o.n > 10000000)
                return usage_error("--n takes a whole number from 2 to 10000000, got '%s'", argv[i]);
        } else if (!strncmp(a, "--", 2) && !has_value && (!strcmp(a, "--params") || !strcmp(a, "--precision") ||
                                                           !strcmp(a, "--grid") || !strcmp(a, "--orientation") ||
                                                           !strcmp(a, "--z") || !strcmp(a, "--n"))) {
            return usage_error("option %s needs a value", a);
        } else {
            return usage_error("unexpected argument '%s'", a);
        }
    }

    kin_param_values p;
    kin_params_default(&p);
    if (o.params_path) {
        char err[512];
        if (kin_params_load(o.params_path, &p, err, sizeof err) != 0) {
            fprintf(stderr, "tse-kin: %s\n", err);
            return EXIT_FILE;
        }
    }
    if (!strcmp(cmd, "bench"))
        return cmd_bench(&p, o.n);
    kin_ctx *ctx = o.ops->create(&p);
    if (!ctx) {
        fprintf(stderr, "tse-kin: invalid parameter set\n");
        return EXIT_FILE;
    }
    int rc = 0;
    if (!strcmp(cmd, "ik"))
        rc = cmd_ik(o.ops, ctx, 0);
    else if (!strcmp(cmd, "jacobian"))
        rc = cmd_ik(o.ops, ctx, 1);
    else if (!strcmp(cmd, "fk"))
        rc = cmd_fk(o.ops, ctx);
    else if (!strcmp(cmd, "haf"))
        rc = cmd_haf(o.ops, ctx, &p, o.zs);
    else
        rc = cmd_workspace(o.ops, ctx, o.grid, o.orientation);
    o.ops->destroy(ctx);
    return rc;
}
