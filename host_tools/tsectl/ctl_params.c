#include "ctl_params.h"

int ctl_param_get(tlink *l, int id, int32_t *value)
{
    const int32_t v[1] = {id};
    if (link_send(l, PM_PARAM_GET, v) != 0) {
        ctl_error("cannot send on the bus");
        return EXIT_BUS;
    }
    proto_message m;
    const int rc = ctl_answer(l, proto_table[PM_PARAM_GET].function, -1, NULL, &m);
    if (rc == EXIT_REJECTED)
        ctl_print_reject(&m);
    if (rc != EXIT_OK)
        return rc;
    const uint64_t end = link_now_us() + (uint64_t)tsectl_timeout_ms * 1000u;
    while (link_now_us() < end && !tsectl_interrupted)
        if (link_recv(l, &m, 50) == 1 && m.msg == PM_PARAM_VALUE && m.v[0] == id) {
            *value = m.v[1];
            return EXIT_OK;
        }
    ctl_error("no PARAM_VALUE for parameter %s from node %u", id < FP_COUNT ? fw_param_table[id].name : "?", l->node);
    return tsectl_interrupted ? EXIT_INTERRUPTED : EXIT_TIMEOUT;
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
