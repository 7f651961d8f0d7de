#include "kin_icount_stub.h"

tse_status icount_stub_ik(const tse_geometry *g, const tse_real pose[6], const tse_real seed_q[6],
                          tse_ik_result *out)
{
    (void)g;
    (void)pose;
    (void)seed_q;
    (void)out;
    return TSE_OK;
}

tse_status icount_stub_fk(const tse_geometry *g, const tse_real q[6], const tse_real seed_pose[6],
                          tse_fk_result *out)
{
    (void)g;
    (void)q;
    (void)seed_pose;
    (void)out;
    return TSE_OK;
}
