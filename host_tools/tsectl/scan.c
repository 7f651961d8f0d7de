#include "scan.h"

#include <string.h>

/* What a scan reads: the answers to INFO_GET, and STATUS, which a controller sends whatever it
 * is busy with. */
static const proto_msg heard[] = {PM_ACK, PM_REJECT, PM_INFO, PM_BOARD, PM_STATUS};

static void take(scan_entry *e, const proto_message *m)
{
    const uint8_t info_get = proto_table[PM_INFO_GET].function;
    e->heard = true;
    switch (m->msg) {
    case PM_INFO:
        e->info = true;
        ++e->infos;
        e->about = (ctl_info){(int)m->v[0], (int)m->v[1], (int)m->v[2], {(uint32_t)m->v[3], (uint32_t)m->v[4]}};
        break;
    case PM_BOARD:
        e->board = true;
        for (int k = 0; k < 8; ++k)
            e->name[k] = (char)m->v[k];
        e->name[8] = '\0';
        break;
    case PM_REJECT:
        if (m->v[0] != info_get)
            break;
        /* An older firmware: unknown for both pages before INFO, range for page 1 before BOARD. */
        if (m->v[2] == FW_REASON_UNKNOWN)
            e->info_unknown = true;
        else
            e->board_refused = true;
        break;
    default:
        break;
    }
}

static bool done(const scan_entry *e)
{
    return e->info_unknown || (e->info && (e->board || e->board_refused));
}

int scan_nodes(tlink *l, uint16_t nodes, int wait_ms, scan_entry out[16])
{
    memset(out, 0, 16 * sizeof out[0]);
    if (link_listen_any(l, heard, (int)(sizeof heard / sizeof heard[0])) != 0) {
        ctl_error("cannot set the CAN socket's filter");
        return EXIT_BUS;
    }
    int rc = EXIT_OK;
    for (uint8_t k = 1; k <= PROTO_NODE_MASK && rc == EXIT_OK; ++k)
        for (int32_t page = 0; page <= 1 && (nodes >> k & 1u); ++page)
            if (link_send_to(l, k, PM_INFO_GET, &page) != 0) {
                ctl_error("cannot send on the bus");
                rc = EXIT_BUS;
            }
    const uint64_t end = link_now_us() + (uint64_t)wait_ms * 1000u;
    while (rc == EXIT_OK && !tsectl_interrupted && link_now_us() < end) {
        proto_message m;
        if (link_recv(l, &m, 20) != 1 || m.node == PROTO_BROADCAST)
            continue;
        take(&out[m.node], &m);
        bool all = true;
        for (int k = 1; k <= (int)PROTO_NODE_MASK; ++k)
            all = all && (!(nodes >> k & 1u) || done(&out[k]));
        if (all)
            break;
    }
    l->any_node = false;
    if (link_telemetry(l, false) != 0 && rc == EXIT_OK) {
        ctl_error("cannot set the CAN socket's filter");
        rc = EXIT_BUS;
    }
    return rc;
}
