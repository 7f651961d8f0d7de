#define _POSIX_C_SOURCE 200809L
#include "path_plot.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "fw/limits.h"
#include "traj_checker.h"
#include "tse/ik.h"

/* Debian's interpreter: the one python3-matplotlib installs into. */
#define PLOT_PYTHON "/usr/bin/python3"

/* Reads "t,x,y,z,v1..v6" rows after a first line "vmax" from stdin, draws into argv[1]. */
static const char script[] =
    "import sys\n"
    "import matplotlib\n"
    "matplotlib.use('Agg')\n"
    "import matplotlib.pyplot as plt\n"
    "vmax = float(sys.stdin.readline())\n"
    "rows = [[float(x) for x in line.split(',')] for line in sys.stdin if line.strip()]\n"
    "t = [r[0] for r in rows]\n"
    "fig, (a, b, c) = plt.subplots(1, 3, figsize=(15, 4.5))\n"
    "a.plot([r[1] * 1e3 for r in rows], [r[2] * 1e3 for r in rows], '.-', ms=3)\n"
    "a.set_xlabel('x [mm]'); a.set_ylabel('y [mm]'); a.set_aspect('equal', 'datalim')\n"
    "a.set_title('plate path from above (a point per row)')\n"
    "b.plot(t, [r[3] * 1e3 for r in rows])\n"
    "b.set_xlabel('t [s]'); b.set_ylabel('z [mm]'); b.set_title('plate height')\n"
    "for k, name in enumerate(['A1', 'B1', 'A2', 'B2', 'A3', 'B3']):\n"
    "    c.plot(t, [r[4 + k] for r in rows], label=name)\n"
    "c.axhline(vmax, color='k', ls='--', label='limit')\n"
    "c.set_xlabel('t [s]'); c.set_ylabel('|slide speed| [m/s]'); c.set_title('slide speeds, row by row')\n"
    "c.legend(fontsize=8)\n"
    "fig.tight_layout()\n"
    "fig.savefig(sys.argv[1], dpi=100)\n";

/* Runs python3 -c prog [arg] with text on its stdin (NULL: none).  Returns its exit status, or -1. */
static int run_python(const char *prog, const char *arg, const plan *p, const fw_param_set *s, fw_rates r, char *err,
                      size_t errlen)
{
    int fd[2];
    if (pipe(fd) != 0) {
        snprintf(err, errlen, "cannot make a pipe: %s", strerror(errno));
        return -1;
    }
    const pid_t pid = fork();
    if (pid < 0) {
        close(fd[0]);
        close(fd[1]);
        snprintf(err, errlen, "cannot start %s: %s", PLOT_PYTHON, strerror(errno));
        return -1;
    }
    if (pid == 0) {
        dup2(fd[0], 0);
        close(fd[0]);
        close(fd[1]);
        execl(PLOT_PYTHON, "python3", "-c", prog, arg, (char *)NULL);
        _exit(127);
    }
    close(fd[0]);
    FILE *f = fdopen(fd[1], "w");
    if (f && p) {
        tse_geometry g;
        fw_limits lim;
        double q[6], prev_q[6], prev_t = 0.0;
        traj_limits(s, r, &g, &lim);
        plan_start_slides(p, q);
        memcpy(prev_q, q, sizeof q);
        fprintf(f, "%.9g\n", (double)lim.slide_vmax);
        plan_cursor c;
        plan_row row;
        for (plan_rows_begin(p, &c); plan_rows_next(p, &c, &row);) {
            tse_ik_result ik;
            if (tse_ik(&g, row.pose, prev_q, &ik) == TSE_OK)
                memcpy(q, ik.q, sizeof q);
            fprintf(f, "%.6f,%.9g,%.9g,%.9g", row.t, row.pose[0], row.pose[1], row.pose[2]);
            for (int k = 0; k < 6; ++k)
                fprintf(f, ",%.9g", fabs(q[k] - prev_q[k]) / (row.t - prev_t));
            fputc('\n', f);
            memcpy(prev_q, q, sizeof q);
            prev_t = row.t;
        }
    }
    /* The data reached the plotter whole, or the plot is not taken as drawn. */
    const int sent = f ? fclose(f) : (close(fd[1]), -1);
    int status;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    if (sent != 0 && p) {
        snprintf(err, errlen, "the data for the plot did not reach %s whole", PLOT_PYTHON);
        return -1;
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

int path_plot_available(char *err, size_t errlen)
{
    if (access(PLOT_PYTHON, X_OK) != 0 || run_python("import matplotlib", NULL, NULL, NULL, FW_RATES_BUILT_IN, err, errlen) != 0) {
        snprintf(err, errlen, "--plot needs %s with matplotlib (Debian's python3-matplotlib: scripts/setup.sh)",
                 PLOT_PYTHON);
        return -1;
    }
    return 0;
}

int path_plot(const plan *p, const fw_param_set *s, fw_rates r, const char *png, char *err, size_t errlen)
{
    const int rc = run_python(script, png, p, s, r, err, errlen);
    if (rc != 0) {
        if (rc > 0)
            snprintf(err, errlen, "%s could not draw %s (python3 exited %d)", PLOT_PYTHON, png, rc);
        return -1;
    }
    return 0;
}
