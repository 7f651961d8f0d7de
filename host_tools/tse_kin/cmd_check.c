/* `tse-kin check`: a trajectory file judged by the controller's own validator, offline: what
 * `tsectl trajectory` checks before sending, from rest at the file's first row. */
#include <stdio.h>
#include <stdlib.h>

#include "commands.h"
#include "controller_set.h"
#include "fw/limits.h"
#include "fw/proto_table.h"
#include "reject_text.h"
#include "traj_check.h"
#include "traj_checker.h"
#include "tse/ik.h"

_Static_assert(FW_STEP_HZ == 200000u && FW_SEGMENT_HZ == 1000u, "the help below says the built-in rates");

const char cmd_check_help[] =
    "usage: tse-kin check [--params FILE] TRAJ.csv\n"
    "\n"
    "Judges a trajectory file (t,x,y,z,roll,pitch,yaw, as tsectl trajectory reads it) with the\n"
    "controller's own validator, from rest at the file's first row: every row reachable with both\n"
    "singularity margins, the slides within their speed and acceleration limits as the controller\n"
    "measures them at the controller's built-in rates (200 kHz step interrupts, 1 kHz control\n"
    "segments; tsectl trajectory checks at the rates a controller reports in INFO). A refused row is\n"
    "named as tsectl names it:\n"
    "  FILE:LINE: row N (t = T s) would be refused: rejected: timing: ...\n"
    "with the slide, the limit and by how much; an accepted file gives one line with the peaks.\n"
    "\n"
    "--params FILE: the controller's parameter file (as tse-sim and 'tsectl params dump' write it);\n"
    "default: the controller's defaults.\n"
    "\n"
    "Exit status: 0 accepted, 1 unreadable or invalid file, 2 usage error, 3 refused.\n";

int cmd_check(const kin_run *run)
{
    const char *path = run->opt->args[0];
    fw_param_set set;
    int rc = kin_controller_set(run, &set);
    if (rc != KIN_EXIT_OK)
        return rc;
    traj_row *rows;
    char err[768];
    const int n = traj_file_read(path, &rows, err, sizeof err);
    if (n < 0) {
        fprintf(stderr, "tse-kin: %s\n", err);
        return KIN_EXIT_FILE;
    }
    tse_geometry g;
    fw_limits lim;
    tse_ik_result ik;
    traj_check_result chk;
    const fw_rates rates = FW_RATES_BUILT_IN;
    if (traj_limits(&set, rates, &g, &lim) != 0) {
        fprintf(stderr, "tse-kin: %s: the controller would refuse the parameter set itself\n",
                run->opt->params_path ? run->opt->params_path : "the defaults");
        rc = KIN_EXIT_FILE;
    } else if (tse_ik(&g, rows[0].p, NULL, &ik) != TSE_OK) {
        fprintf(stderr, "tse-kin: %s:%d: row 1, where the check starts, is outside the workspace (%s, scissor %d)\n",
                path, rows[0].line, tse_status_name(ik.status), ik.scissor);
        rc = KIN_EXIT_REFUSED;
    } else {
        const int c = traj_check(&set, rates, rows[0].p, ik.q, rows, n, &chk);
        if (c != 0) {
            char text[512];
            fprintf(stderr, "tse-kin: %s:%d: row %d (t = %.6g s) would be refused: %s\n", path, rows[chk.row].line,
                    chk.row + 1, rows[chk.row].t, reject_text(&chk.why, text, sizeof text));
            rc = KIN_EXIT_REFUSED;
        } else {
            printf("%s: %d rows accepted from rest at row 1: slide speed up to %.1f%% of the %.4g m/s in effect (%s), "
                   "acceleration up to %.1f%% of slide_amax\n",
                   path, n, chk.v_peak * 100.0, chk.v_limit, proto_slide_limits[chk.v_by].name, chk.a_peak * 100.0);
        }
    }
    free(rows);
    return rc;
}
