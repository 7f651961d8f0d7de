#include "traj_check.h"

#include <string.h>

#include "fw/limits.h"
#include "fw/reject.h"
#include "fw/traj.h"

uint32_t traj_dt_us(const traj_row *rows, int i)
{
    /* The reader checked exactly these differences (traj_file.h). */
    return (uint32_t)(traj_time_us(rows[i].t) - (i > 0 ? traj_time_us(rows[i - 1].t) : 0));
}

int traj_check(const fw_param_set *s, const double pose0[6], const double q0[6], const traj_row *rows, int n,
               traj_check_result *r)
{
    static fw_traj t; /* large: off the stack */
    tse_geometry g;
    fw_limits lim;
    memset(r, 0, sizeof *r);
    r->row = -1;
    if (fw_limits_from_params(s, TSECTL_STEP_HZ, TSECTL_SEGMENT_HZ, &g, &lim) != 0)
        return -1;
    r->v_limit = (double)lim.slide_vmax;
    r->v_by = lim.vmax_by;
    tse_real pose[6], q[6];
    for (int k = 0; k < 6; ++k) {
        pose[k] = (tse_real)pose0[k];
        q[k] = (tse_real)q0[k];
    }
    fw_traj_start(&t, &lim, pose, q);
    for (int i = 0; i < n; ++i) {
        tse_real p[6];
        for (int k = 0; k < 6; ++k)
            p[k] = (tse_real)rows[i].p[k];
        fw_plan_result why;
        if (fw_traj_push(&t, &g, &lim, p, traj_dt_us(rows, i), i == n - 1, &why) != 0) {
            r->row = i;
            r->why.msg = PM_REJECT;
            fw_reject_values(proto_table[PM_TRAJ_COMMIT].function, 0, why.reason, 0, &why, r->why.v);
            r->v_peak = (double)t.chk.v_ratio;
            r->a_peak = (double)t.chk.a_ratio;
            return 1;
        }
        /* The queue holds what execution has not reached; here nothing runs, so drain it. */
        tse_real at[6];
        fw_traj_pose(&t, fw_traj_end_us(&t), at);
    }
    r->v_peak = (double)t.chk.v_ratio;
    r->a_peak = (double)t.chk.a_ratio;
    return 0;
}
