#include "ctl_params.h"

#include <stdio.h>

int ctl_param_get(tlink *l, int id, int32_t *value)
{
    const int32_t v[1] = {id};
    char what[64];
    snprintf(what, sizeof what, "PARAM_VALUE for parameter %s", id < FP_COUNT ? fw_param_table[id].name : "?");
    proto_message m;
    const int rc = ctl_ask(l, PM_PARAM_GET, v, PM_PARAM_VALUE, id, what, &m);
    if (rc == EXIT_REJECTED)
        ctl_print_reject(&m);
    if (rc == EXIT_OK)
        *value = m.v[1];
    return rc;
}

int ctl_params_read(tlink *l, fw_param_set *s)
{
    for (int id = 0; id < FP_COUNT; ++id) {
        const int rc = ctl_param_get(l, id, &s->v[id]);
        if (rc != EXIT_OK)
            return rc;
    }
    return EXIT_OK;
}
