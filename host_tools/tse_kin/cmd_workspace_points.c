/* `tse-kin workspace --points`: the grid points themselves, so that the workspace can be drawn.
 *
 * Promise: '#' comment lines, the header "x,y,z,status,scissor", one row per grid point in the
 * order tse_workspace visits them (Z, then r, then phi), and last a '#' line with the count and
 * the volume of their cells; the rows whose status is ok are exactly the points `tse-kin workspace`
 * counts on the same grid, and their cells its volume (to rounding: it sums ring by ring). */
#include <math.h>
#include <stdio.h>

#include "commands.h"
#include "csv.h"
#include "progress.h"

int cmd_workspace_points(const kin_run *run)
{
    const int *g = run->opt->grid;
    const double *o = run->opt->orientation;
    const long total = (long)g[0] * g[1] * g[2];
    kin_workspace_comments(run);
    printf("# status and scissor as tse-kin ik answers the point\n");
    printf("x,y,z,status,scissor\n");
    kin_progress bar;
    kin_progress_start(&bar, "workspace", total);
    long reachable = 0, done = 0;
    double volume = 0;
    for (int k = 0; k < g[2]; ++k)
        for (int i = 0; i < g[0]; ++i) {
            double cell = NAN;
            (void)run->ops->workspace_cell(run->ctx, g, i, k, &cell);
            for (int j = 0; j < g[1]; ++j) {
                double pose[6];
                int scissor;
                const tse_status st = run->ops->workspace_point(run->ctx, g, i, j, k, o, pose, &scissor);
                /* + 0.0 turns the -0 of r = 0 at phi = pi into 0: one spelling of the axis. */
                const double xyz[3] = {pose[0] + 0.0, pose[1] + 0.0, pose[2] + 0.0};
                csv_put_number(stdout, xyz[0]);
                csv_put_numbers(stdout, xyz + 1, 2);
                printf(",%s,%d\n", tse_status_name(st), scissor);
                if (st == TSE_OK) {
                    ++reachable;
                    volume += cell;
                }
                if ((++done & 1023) == 0)
                    kin_progress_update(&bar, done);
            }
        }
    kin_progress_end(&bar);
    printf("# reachable,total,fraction,volume_m3: %ld,%ld,%.6f,", reachable, total,
           total > 0 ? (double)reachable / (double)total : 0.0);
    csv_put_number(stdout, volume);
    printf("%s\n", kin_params_is_prototype(run->params) ? " (paper: " KIN_PAPER_WORKSPACE " for the prototype)" : "");
    if (fflush(stdout) != 0 || ferror(stdout)) {
        fprintf(stderr, "tse-kin: error writing the output\n");
        return KIN_EXIT_FILE;
    }
    return KIN_EXIT_OK;
}
