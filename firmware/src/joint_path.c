#include "fw/joint_path.h"

#include <stdint.h>

#include "tse/fk.h"

tse_status fw_joint_path_check(const tse_geometry *g, const tse_real from[6], tse_real *where, int *scissor)
{
    tse_real seed[6];
    for (int k = 0; k < 6; ++k)
        seed[k] = g->home_pose[k];
    *where = TSE_R(0.0);
    *scissor = 0;
    for (uint32_t i = FW_JOINT_PATH_SAMPLES + 1u; i-- > 0u;) {
        const tse_real u = (tse_real)i / (tse_real)FW_JOINT_PATH_SAMPLES;
        tse_real q[6];
        for (int k = 0; k < 6; ++k)
            q[k] = from[k] + u * (g->home_s - from[k]);
        tse_fk_result r;
        if (tse_fk(g, q, seed, &r) != TSE_OK) {
            *where = u;
            *scissor = r.scissor;
            return r.status;
        }
        for (int k = 0; k < 6; ++k)
            seed[k] = r.pose[k];
    }
    return TSE_OK;
}
