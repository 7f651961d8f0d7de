/* `tse-kin workspace --points`: the grid points themselves, so that the workspace can be drawn.
 *
 * Promise: '#' comment lines, the header "x,y,z,status,scissor", one row per grid point in the
 * order tse_workspace visits them (Z, then r, then phi), and last a '#' line with the count; the
 * rows whose status is ok are exactly the points `tse-kin workspace` counts on the same grid. */
#include <stdio.h>

#include "commands.h"
#include "csv.h"
#include "progress.h"

int cmd_workspace_points(const kin_run *run)
{
    const int *g = run->opt->grid;
    const double *o = run->opt->orientation;
    const long total = (long)g[0] * g[1] * g[2];
    printf("# grid %d x %d x %d (r, phi, Z) = %ld points: r_i = (L/2) i/(NR-1), phi_j = 2 pi j/NPHI, "
           "Z_k = L k/(NZ-1)\n",
           g[0], g[1], g[2], total);
    printf("# orientation %.17g,%.17g,%.17g rad; precision %s; status and scissor as tse-kin ik answers the point\n",
           o[0], o[1], o[2], run->ops->name);
    printf("x,y,z,status,scissor\n");
    kin_progress bar;
    kin_progress_start(&bar, "workspace", total);
    long reachable = 0, done = 0;
    for (int k = 0; k < g[2]; ++k)
        for (int i = 0; i < g[0]; ++i)
            for (int j = 0; j < g[1]; ++j) {
                double pose[6];
                int scissor;
                const tse_status st = run->ops->workspace_point(run->ctx, g, i, j, k, o, pose, &scissor);
                /* + 0.0 turns the -0 of r = 0 at phi = pi into 0: one spelling of the axis. */
                const double xyz[3] = {pose[0] + 0.0, pose[1] + 0.0, pose[2] + 0.0};
                csv_put_number(stdout, xyz[0]);
                csv_put_numbers(stdout, xyz + 1, 2);
                printf(",%s,%d\n", tse_status_name(st), scissor);
                reachable += st == TSE_OK;
                if ((++done & 1023) == 0)
                    kin_progress_update(&bar, done);
            }
    kin_progress_end(&bar);
    printf("# reachable,total,fraction: %ld,%ld,%.6f (paper: 0.28 for the prototype)\n", reachable, total,
           total > 0 ? (double)reachable / (double)total : 0.0);
    if (fflush(stdout) != 0 || ferror(stdout)) {
        fprintf(stderr, "tse-kin: error writing the output\n");
        return KIN_EXIT_FILE;
    }
    return KIN_EXIT_OK;
}
