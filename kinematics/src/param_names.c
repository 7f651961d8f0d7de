#include "tse/params.h"

static const char *const param_names[TSE_PARAM_COUNT] = {
    "none", "L", "k1", "eta", "k3", "k4", "alpha_min", "alpha_max", "s_min", "s_max", "mu_min", "nu_min",
};

const char *tse_param_name(tse_param_id id)
{
    if ((unsigned)id >= (unsigned)TSE_PARAM_COUNT)
        return "?";
    return param_names[id];
}
