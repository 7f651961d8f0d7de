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

int ctl_param_set(tlink *l, int id, int32_t raw, int32_t *now, proto_message *reject)
{
    const int32_t v[2] = {id, raw};
    if (link_send(l, PM_PARAM_SET, v) != 0) {
        ctl_error("cannot send on the bus");
        return EXIT_BUS;
    }
    const int rc = ctl_answer(l, proto_table[PM_PARAM_SET].function, -1, NULL, reject);
    if (rc != EXIT_OK)
        return rc;
    proto_message m;
    const uint64_t end = link_now_us() + (uint64_t)tsectl_timeout_ms * 1000u;
    while (link_now_us() < end)
        if (link_recv(l, &m, 50) == 1 && m.msg == PM_PARAM_VALUE && m.v[0] == id) {
            *now = m.v[1];
            return EXIT_OK;
        }
    ctl_error("no PARAM_VALUE after the set was acknowledged");
    return EXIT_TIMEOUT;
}

int ctl_params_save(tlink *l)
{
    const int32_t v[1] = {(int32_t)proto_table[PM_PARAM_SAVE].fields[0].min}; /* its one magic */
    if (link_send(l, PM_PARAM_SAVE, v) != 0) {
        ctl_error("cannot send on the bus");
        return EXIT_BUS;
    }
    proto_message rej;
    const int rc = ctl_answer(l, proto_table[PM_PARAM_SAVE].function, -1, NULL, &rej);
    if (rc == EXIT_REJECTED)
        ctl_print_reject(&rej);
    return rc;
}
