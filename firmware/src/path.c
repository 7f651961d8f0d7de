#include "fw/path.h"

#include "fw/quat.h"

void fw_move_pose_at(const fw_move *mv, tse_real u, tse_real pose[6])
{
    for (int k = 0; k < 3; ++k)
        pose[k] = mv->from[k] + u * mv->dp[k];
    tse_real q[4];
    fw_quat_slerp(mv->q0, mv->q1, u, q);
    fw_quat_to_rpy(q, &pose[3]);
}

void fw_move_pose(const fw_move *mv, tse_real t, tse_real pose[6])
{
    tse_real u, du, ddu;
    fw_profile_eval(&mv->prof, t, &u, &du, &ddu);
    if (t >= mv->prof.T) {
        for (int k = 0; k < 6; ++k)
            pose[k] = mv->to[k]; /* the end is the commanded pose, bit for bit */
        return;
    }
    fw_move_pose_at(mv, u, pose);
}

tse_real fw_move_segment_time(const fw_move *mv, const fw_limits *lim, uint32_t k)
{
    if (k >= mv->segments)
        return mv->prof.T;
    return (tse_real)k / lim->segment_hz;
}
