#include "traj_check.h"

#include <string.h>

#include "traj_checker.h"

uint32_t traj_dt_us(const traj_row *rows, int i)
{
    /* The reader checked exactly these differences (traj_file.h). */
    return (uint32_t)(traj_time_us(rows[i].t) - (i > 0 ? traj_time_us(rows[i - 1].t) : 0));
}

int traj_check(const fw_param_set *s, fw_rates rates, const double pose0[6], const double q0[6], const traj_row *rows,
               int n, traj_check_result *r)
{
    static traj_checker c; /* large: off the stack */
    memset(r, 0, sizeof *r);
    r->row = -1;
    if (traj_checker_start(&c, s, rates, pose0, q0) != 0)
        return -1;
    r->v_limit = (double)c.lim.slide_vmax;
    r->v_by = c.lim.vmax_by;
    int rc = 0;
    for (int i = 0; i < n && rc == 0; ++i) {
        if (traj_checker_push(&c, traj_dt_us(rows, i), rows[i].p, i == n - 1, r->why.v) != 0) {
            r->row = i;
            r->why.msg = PM_REJECT;
            rc = 1;
        }
    }
    traj_checker_peaks(&c, &r->v_peak, &r->a_peak);
    return rc;
}
