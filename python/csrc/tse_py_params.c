/* Names, tables and tse-kin's parameter file for tse.kin, precision independent: see tse_py.h. */
#include "tse_py.h"

#include <string.h>

#include "kin_params_file.h"
#include "tse/status.h"

int tse_py_status_count(void)
{
    return TSE_STATUS_COUNT;
}

const char *tse_py_status_name(int status)
{
    return tse_status_name((tse_status)status);
}

int tse_py_param_count(void)
{
    return TSE_PY_NPARAMS;
}

const char *tse_py_param_name(int id)
{
    return tse_param_name((tse_param_id)id);
}

const char *tse_py_param_key(int i, int *id, int *degrees, const char **rule)
{
    const kin_param_key_def *keys;
    const int n = kin_param_keys(&keys);
    if (i < 0 || i >= n)
        return NULL;
    *id = (int)keys[i].id;
    *degrees = keys[i].degrees;
    *rule = keys[i].rule;
    return keys[i].key;
}

void tse_py_params_default(double v[TSE_PY_NPARAMS])
{
    kin_param_values p;
    kin_params_default(&p);
    memcpy(v, p.v + 1, TSE_PY_NPARAMS * sizeof v[0]);
}

int tse_py_params_load(const char *path, int design, double v[TSE_PY_NPARAMS], char *err, size_t errlen)
{
    kin_param_values p;
    kin_params_default(&p);
    if (errlen > 0)
        err[0] = '\0';
    const kin_params_outcome r = kin_params_load(path, design ? KIN_PARAMS_DESIGN : KIN_PARAMS_CONTROLLER, &p, err, errlen);
    if (r == KIN_PARAMS_OK)
        memcpy(v, p.v + 1, TSE_PY_NPARAMS * sizeof v[0]);
    return (int)r;
}
