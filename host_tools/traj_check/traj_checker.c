#include "traj_checker.h"

#include <math.h>

#include "fw/limits.h"
#include "fw/reject.h"

int traj_limits(const fw_param_set *s, fw_rates r, tse_geometry *g, fw_limits *lim)
{
    return fw_rates_run(r) ? fw_limits_from_params(s, r.step_hz, r.segment_hz, g, lim) : -1;
}

int traj_checker_start(traj_checker *c, const fw_param_set *s, fw_rates r, const double pose0[6],
                       const double q0[6])
{
    if (traj_limits(s, r, &c->g, &c->lim) != 0)
        return -1;
    tse_real pose[6], q[6];
    for (int k = 0; k < 6; ++k) {
        pose[k] = (tse_real)pose0[k];
        q[k] = (tse_real)q0[k];
    }
    fw_traj_start(&c->t, &c->lim, pose, q);
    return 0;
}

int traj_checker_push(traj_checker *c, uint32_t dt_us, const double pose[6], bool last,
                      int32_t reject[PROTO_MAX_FIELDS])
{
    /* What the controller makes of the staged parts (commands.c): the wire's micro-units. */
    tse_real p[6];
    for (int k = 0; k < 6; ++k)
        p[k] = (tse_real)lround(pose[k] * proto_pose_units(k)) * (TSE_R(1.0) / (tse_real)proto_pose_units(k));
    fw_plan_result why;
    if (fw_traj_push(&c->t, &c->g, &c->lim, p, dt_us, last, &why) != 0) {
        fw_reject_values(proto_table[PM_TRAJ_COMMIT].function, 0, why.reason, 0, &why, reject);
        return 1;
    }
    /* The queue holds what execution has not reached; here nothing runs, so drain it. */
    tse_real at[6];
    fw_traj_pose(&c->t, fw_traj_end_us(&c->t), at);
    return 0;
}

void traj_checker_peaks(const traj_checker *c, double *v_peak, double *a_peak)
{
    *v_peak = (double)c->t.check.chk.v_ratio;
    *a_peak = (double)c->t.check.chk.a_ratio;
}

void traj_checker_take_peaks(traj_checker *c, double *v_peak, double *a_peak)
{
    traj_checker_peaks(c, v_peak, a_peak);
    c->t.check.chk.v_ratio = c->t.check.chk.a_ratio = TSE_R(0.0);
}
