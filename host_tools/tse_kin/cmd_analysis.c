/* `tse-kin haf` and `tse-kin workspace`: the paper's design figures, beside the paper's values
 * when the design is its prototype.
 *
 * Promise: lines starting with '#' are commentary; every other line is CSV, and the last line is
 * the summary a script reads (haf: "haf,mean,min,max", then ",paper,11.487" for the prototype
 * only; workspace: "reachable,total,fraction,volume_m3").  The figures are what the library
 * computes, whatever the paper says. */
#include <math.h>
#include <stdio.h>

#include "commands.h"
#include "csv.h"
#include "haf_heights.h"

const char cmd_haf_help[] =
    "usage: tse-kin haf [--params|--design FILE] [--precision float|double] [--z Z1,Z2,...]\n"
    "\n"
    "Vertical spatial gear ratio and Height Amplification Factor (docs/kinematics.md). At each\n"
    "height Z (metres; default: 9 heights spread over L sin(alpha_min) .. L sin(alpha_max), 5 % of\n"
    "the range in from either stop) prints\n"
    "  z,sigma_z,sigma_z_k1_1,haf\n"
    "sigma_z = 1/(sqrt(6)|ds/dZ|) at X = Y = 0, zero orientation; sigma_z_k1_1 the same for the same\n"
    "design with k1 = 1; haf = tse_haf, their ratio. A height without a branch solution gives nan.\n"
    "Then a '#' line with mean, min and max HAF, and last the line\n"
    "  haf,MEAN,MIN,MAX\n"
    "(nan,nan,nan when no height had a value). When the design is the paper's prototype (every\n"
    "kinematic value the default), the paper's figure is named beside ours ('paper: 11.487') and\n"
    "the last line ends ',paper,11.487'. Lines starting with '#' are comments.\n"
    "\n" KIN_HELP_PARAMS "\n" KIN_HELP_EXIT;

const char cmd_workspace_help[] =
    "usage: tse-kin workspace [--grid NR,NPHI,NZ] [--orientation R,P,Y] [--params|--design FILE]\n"
    "                         [--precision float|double] [--points]\n"
    "\n"
    "Workspace percentage of the paper: counts the reachable points (status ok) of the cylindrical\n"
    "grid r_i = (L/2) i/(NR-1), phi_j = 2 pi j/NPHI, Z_k = L k/(NZ-1) at the fixed orientation\n"
    "R,P,Y (radians, default 0,0,0). Default grid 21,36,41 (30996 points). NR >= 2, NPHI >= 1,\n"
    "NZ >= 2, whole numbers. Also the workspace as a volume: the reachable volume of the plate's\n"
    "centre at that orientation, the sum of the cells of the reachable points (each point stands\n"
    "for its cell of the cylinder r <= L/2, 0 <= Z <= L, cut halfway between neighbouring points\n"
    "and into NPHI sectors; the cells fill the cylinder, pi L^3/4), so that designs of different\n"
    "size compare. Prints '#' lines describing the grid, the cylinder and the cells' size (the\n"
    "volume's resolution), then a '#' line naming the columns (beside the paper's 0.28 when the\n"
    "design is its prototype), and last\n"
    "  reachable,total,fraction,volume_m3\n"
    "with the fraction as %.6f.\n"
    "\n"
    "With --points, prints the grid points themselves instead, so that the workspace can be drawn:\n"
    "'#' lines, the header and one row per point (Z, then r, then phi, as they are counted)\n"
    "  x,y,z,status,scissor\n"
    "with status and scissor as tse-kin ik answers the point (ok rows are the reachable points), and\n"
    "last a '#' line with reachable,total,fraction,volume_m3. A progress bar goes to stderr when it is a\n"
    "terminal and the grid takes more than a second.\n"
    "\n" KIN_HELP_PARAMS "\n" KIN_HELP_EXIT;

static int finish(void)
{
    if (fflush(stdout) != 0 || ferror(stdout)) {
        fprintf(stderr, "tse-kin: error writing the output\n");
        return KIN_EXIT_FILE;
    }
    return KIN_EXIT_OK;
}

int cmd_haf(const kin_run *run)
{
    double z[KIN_MAX_Z];
    int n = run->opt->n_z;
    if (n > 0) {
        for (int i = 0; i < n; ++i)
            z[i] = run->opt->z[i];
    } else {
        n = kin_haf_default_heights(run->params, z);
    }

    /* The reference design of the HAF: the same one with the lowest link as long as the scissor. */
    kin_param_values rigid = *run->params;
    rigid.v[TSE_PARAM_K1] = 1.0;
    rigid.line[TSE_PARAM_K1] = 0;
    tse_param_id bad;
    kin_ctx *rctx = run->ops->create(&rigid, &bad);
    if (!rctx) {
        char err[512];
        kin_params_describe_invalid(&rigid, bad, run->params_name, " for the same design with k1 = 1", err,
                                    sizeof err);
        fprintf(stderr, "tse-kin: %s\n", err);
        return KIN_EXIT_FILE;
    }

    printf("# sigma_z = 1/(sqrt(6)|ds/dZ|) at X = Y = 0, zero orientation; HAF = sigma_z / sigma_z(k1 = 1); "
           "precision %s\n",
           run->ops->name);
    printf("# z,sigma_z,sigma_z_k1_1,haf\n");
    double sum = 0, lo = INFINITY, hi = -INFINITY;
    int count = 0;
    for (int i = 0; i < n; ++i) {
        double v[4] = {z[i], NAN, NAN, NAN};
        const tse_status s1 = run->ops->sigma_z(run->ctx, z[i], &v[1]);
        const tse_status s2 = run->ops->sigma_z(rctx, z[i], &v[2]);
        const tse_status s3 = run->ops->haf(run->ctx, z[i], &v[3]);
        csv_put_number(stdout, v[0]);
        csv_put_numbers(stdout, v + 1, 3);
        putchar('\n');
        if (s1 != TSE_OK || s2 != TSE_OK || s3 != TSE_OK || !isfinite(v[3]))
            continue;
        sum += v[3];
        lo = fmin(lo, v[3]);
        hi = fmax(hi, v[3]);
        ++count;
    }
    run->ops->destroy(rctx);
    const int paper = kin_params_is_prototype(run->params);
    if (count == 0) {
        printf("# HAF: no height had a value%s\n", paper ? " (paper: " KIN_PAPER_HAF ")" : "");
        printf("haf,nan,nan,nan%s\n", paper ? ",paper," KIN_PAPER_HAF : "");
        return finish();
    }
    const double mean = sum / count;
    printf("# HAF over %d of %d heights: mean %.6f, min %.6f, max %.6f%s\n", count, n, mean, lo, hi,
           paper ? " (paper: " KIN_PAPER_HAF ")" : "");
    fputs("haf", stdout);
    csv_put_numbers(stdout, (const double[3]){mean, lo, hi}, 3);
    printf("%s\n", paper ? ",paper," KIN_PAPER_HAF : "");
    return finish();
}

void kin_workspace_comments(const kin_run *run)
{
    const int *g = run->opt->grid;
    const double *o = run->opt->orientation;
    const double L = run->params->v[TSE_PARAM_L], pi = 3.14159265358979323846;
    printf("# grid %d x %d x %d (r, phi, Z) = %ld points: r_i = (L/2) i/(NR-1), phi_j = 2 pi j/NPHI, "
           "Z_k = L k/(NZ-1)\n",
           g[0], g[1], g[2], (long)g[0] * g[1] * g[2]);
    printf("# orientation %.17g,%.17g,%.17g rad; precision %s\n", o[0], o[1], o[2], run->ops->name);
    printf("# volume_m3: the reachable volume of the plate's centre at this orientation, the sum of the cells of "
           "the reachable points; the cells fill the cylinder r <= %.6g m, 0 <= Z <= %.6g m (%.6g m^3), cut halfway "
           "between neighbouring points: %.4g m in r, %.4g m in Z, an arc of %.4g m at the rim (the volume's "
           "resolution)\n",
           L / 2, L, pi * L * L * L / 4, L / (2 * (g[0] - 1)), L / (g[2] - 1), pi * L / g[1]);
}

int cmd_workspace(const kin_run *run)
{
    if (run->opt->points)
        return cmd_workspace_points(run);
    const int *g = run->opt->grid;
    const double *o = run->opt->orientation;
    long reachable = 0, total = 0;
    double volume = NAN;
    const tse_status st = run->ops->workspace_volume(run->ctx, g[0], g[1], g[2], o, &reachable, &total, &volume);
    if (st != TSE_OK) {
        /* Options were checked against the same rules, so this is the library disagreeing. */
        fprintf(stderr, "tse-kin: the library refused the grid %d,%d,%d: %s\n", g[0], g[1], g[2],
                tse_status_name(st));
        return KIN_EXIT_FILE;
    }
    kin_workspace_comments(run);
    printf("# reachable,total,fraction,volume_m3%s\n",
           kin_params_is_prototype(run->params) ? " (paper: " KIN_PAPER_WORKSPACE " for the prototype)" : "");
    printf("%ld,%ld,%.6f,", reachable, total, total > 0 ? (double)reachable / (double)total : 0.0);
    csv_put_number(stdout, volume);
    putchar('\n');
    return finish();
}
