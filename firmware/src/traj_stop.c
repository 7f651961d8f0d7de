#include "fw/traj_stop.h"

tse_real fw_traj_stop_time(tse_real v, tse_real amax, tse_real min_T)
{
    const tse_real T = FW_TRAJ_STOP_LN * v / (FW_PATH_MARGIN * amax);
    return T < min_T ? min_T : T;
}

tse_real fw_traj_stop_reach(tse_real T)
{
    return T * (TSE_R(1.0) / FW_PATH_MARGIN - TSE_R(1.0) / FW_TRAJ_STOP_LN);
}

void fw_traj_stop_begin(fw_traj_stop *s, tse_real T, tse_real dt)
{
    /* A ramp stretched to T (the shortest stop, or a speed lower than the path's) keeps the law's
     * shape: k = ln(1 / (1 - m)) / T.  k dt is at most 0.15 (T at least 20 ms, dt 1 ms): four terms
     * of the series give e^(k dt) within 1e-6. */
    const tse_real y = FW_TRAJ_STOP_LN * dt / T;
    s->grow = TSE_R(1.0) + y * (TSE_R(1.0) + y * (TSE_R(0.5) + y * (TSE_R(1.0) / TSE_R(6.0) + y / TSE_R(24.0))));
    s->gap = TSE_R(1.0) - FW_PATH_MARGIN;
}

tse_real fw_traj_stop_next(fw_traj_stop *s)
{
    s->gap *= s->grow;
    const tse_real r = (TSE_R(1.0) - s->gap) / FW_PATH_MARGIN;
    return r > TSE_R(0.0) ? r : TSE_R(0.0);
}
