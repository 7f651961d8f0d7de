#include "tse/params.h"

static const char *const param_names[TSE_PARAM_COUNT] = {
    [TSE_PARAM_OK] = "none",
    [TSE_PARAM_L] = TSE_PARAM_NAME_L,
    [TSE_PARAM_K1] = TSE_PARAM_NAME_K1,
    [TSE_PARAM_ETA] = TSE_PARAM_NAME_ETA,
    [TSE_PARAM_K3] = TSE_PARAM_NAME_K3,
    [TSE_PARAM_K4] = TSE_PARAM_NAME_K4,
    [TSE_PARAM_ALPHA_MIN] = TSE_PARAM_NAME_ALPHA_MIN,
    [TSE_PARAM_ALPHA_MAX] = TSE_PARAM_NAME_ALPHA_MAX,
    [TSE_PARAM_S_MIN] = TSE_PARAM_NAME_S_MIN,
    [TSE_PARAM_S_MAX] = TSE_PARAM_NAME_S_MAX,
    [TSE_PARAM_MU_MIN] = TSE_PARAM_NAME_MU_MIN,
    [TSE_PARAM_NU_MIN] = TSE_PARAM_NAME_NU_MIN,
};

const char *tse_param_name(tse_param_id id)
{
    if ((unsigned)id >= (unsigned)TSE_PARAM_COUNT)
        return "?";
    return param_names[id];
}
