/* `tse-kin profile`: the paper's singular-value figures, along the vertical axis.
 *
 * Promise: '#' comment lines, the header "z,sv1,...,sv6,sigma_z,mu_min,nu", then one row per
 * height in the order given; a height without a branch solution (or a singular one) has nan for
 * every figure.  The figures are of the branch solution with no limit applied, as sigma_z and the
 * HAF are, so a curve runs on through a stop instead of stopping at it. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "commands.h"
#include "csv.h"

/* Enough heights for a smooth curve of the paper's figures. */
enum { PROFILE_DEFAULT_N = 60 };

const char cmd_profile_help[] =
    "usage: tse-kin profile [--params|--design FILE] [--precision float|double] [--z Z1,Z2,...|--n N]\n"
    "\n"
    "The Jacobian's singular values along the vertical axis (the paper's singular-value figures).\n"
    "At each height Z (metres; --z, or --n N heights evenly from L sin(alpha_min) to L sin(alpha_max)\n"
    "inclusive, default 60) of the pose (0, 0, Z, 0, 0, 0), prints\n"
    "  z,sv1,sv2,sv3,sv4,sv5,sv6,sigma_z,mu_min,nu\n"
    "sv1 >= ... >= sv6: the singular values of dp/dq (as tse-kin jacobian prints them: x, y, z in\n"
    "metres, roll, pitch, yaw in radians); sigma_z = 1/(sqrt(6)|ds/dZ|), the one along the motion of\n"
    "all six slides together (tse-kin haf's); mu_min the smallest type-1 margin of the three\n"
    "scissors; nu the type-2 ratio (docs/kinematics.md). They are the branch solution's, with no\n"
    "limit applied; a height without one gives nan for all nine. '#' lines are comments.\n"
    "\n" KIN_HELP_PARAMS "\n" KIN_HELP_EXIT;

int cmd_profile_check(const kin_options *o, char *err, size_t errlen)
{
    if (o->n_z > 0 && o->n_set) {
        snprintf(err, errlen, "profile takes --z or --n, not both");
        return -1;
    }
    return 0;
}

int cmd_profile(const kin_run *run)
{
    const kin_options *o = run->opt;
    const long n = o->n_z > 0 ? o->n_z : o->n_set ? o->bench_n : PROFILE_DEFAULT_N;
    const double L = run->params->v[TSE_PARAM_L];
    const double lo = L * sin(run->params->v[TSE_PARAM_ALPHA_MIN]);
    const double hi = L * sin(run->params->v[TSE_PARAM_ALPHA_MAX]);

    printf("# the pose (0, 0, z, 0, 0, 0); singular values of dp/dq, sigma_z, the smallest type-1 margin and the "
           "type-2 ratio of the branch solution (no limit applied); precision %s\n",
           run->ops->name);
    printf("# alpha stops at z = L sin(alpha_min) = %.6f m and L sin(alpha_max) = %.6f m\n", lo, hi);
    printf("z,sv1,sv2,sv3,sv4,sv5,sv6,sigma_z,mu_min,nu\n");
    for (long i = 0; i < n; ++i) {
        double z;
        if (o->n_z > 0)
            z = o->z[i];
        else
            z = i == n - 1 ? hi : lo + (hi - lo) * ((double)i / (double)(n - 1)); /* both stops exactly */
        kin_profile_out f;
        run->ops->profile(run->ctx, z, &f);
        csv_put_number(stdout, z);
        csv_put_numbers(stdout, f.sv, 6);
        csv_put_numbers(stdout, (const double[3]){f.sigma_z, f.mu_min, f.nu}, 3);
        putchar('\n');
    }
    if (fflush(stdout) != 0 || ferror(stdout)) {
        fprintf(stderr, "tse-kin: error writing the output\n");
        return KIN_EXIT_FILE;
    }
    return KIN_EXIT_OK;
}
