#include "steps.h"

#include "fw/proto_wire.h"

int32_t fw_steps_of(const fw_param_set *p, tse_real s)
{
    const tse_real x = s * (tse_real)p->v[FP_STEPS_PER_M];
    return (int32_t)(x >= TSE_R(0.0) ? x + TSE_R(0.5) : x - TSE_R(0.5));
}

int32_t fw_steps_of_um(const fw_param_set *p, int32_t um)
{
    const int64_t x = (int64_t)um * p->v[FP_STEPS_PER_M];
    return (int32_t)((x >= 0 ? x + 500000 : x - 500000) / 1000000);
}

int32_t fw_switch_steps(const fw_param_set *p, int k)
{
    /* The last whole step at or below the switch (home_sw_k >= s_min >= 0): pressed there. */
    return (int32_t)((int64_t)p->v[FP_HOME_SW_1 + k] * p->v[FP_STEPS_PER_M] / PROTO_UM_PER_M);
}
