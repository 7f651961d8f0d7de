#define _GNU_SOURCE
#include "link.h"

#include <errno.h>
#include <linux/can.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <poll.h>
#include <stdio.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

uint64_t link_now_us(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (uint64_t)t.tv_sec * 1000000u + (uint64_t)t.tv_nsec / 1000u;
}

int link_open(tlink *l, const char *iface, uint8_t node)
{
    memset(l, 0, sizeof *l);
    l->node = node;
    l->fd = socket(PF_CAN, SOCK_RAW, CAN_RAW);
    if (l->fd < 0)
        return -1;
    struct ifreq ifr;
    memset(&ifr, 0, sizeof ifr);
    strncpy(ifr.ifr_name, iface, IFNAMSIZ - 1);
    struct sockaddr_can addr;
    memset(&addr, 0, sizeof addr);
    addr.can_family = AF_CAN;
    if (ioctl(l->fd, SIOCGIFINDEX, &ifr) < 0)
        goto fail;
    addr.can_ifindex = ifr.ifr_ifindex;
    if (link_telemetry(l, false) < 0 || bind(l->fd, (struct sockaddr *)&addr, sizeof addr) < 0)
        goto fail;
    return 0;
fail:;
    const int e = errno;
    close(l->fd);
    l->fd = -1;
    errno = e;
    return -1;
}

static bool is_telemetry(proto_msg m)
{
    return (m >= PM_SLIDES_A && m <= PM_SLIDES_C) || (m >= PM_FK_A && m <= PM_FK_C);
}

int link_telemetry(tlink *l, bool on)
{
    /* The node's frames, either way (low four bits = node): every function, or every function
     * but the telemetry's. */
    struct can_filter f[PM_COUNT];
    int n = 0;
    if (on) {
        f[n++] = (struct can_filter){l->node, CAN_EFF_FLAG | CAN_RTR_FLAG | 0x00F};
    } else {
        for (int m = 0; m < PM_COUNT; ++m)
            if (!is_telemetry((proto_msg)m))
                f[n++] = (struct can_filter){(canid_t)(proto_table[m].function << PROTO_NODE_BITS | l->node),
                                             CAN_EFF_FLAG | CAN_RTR_FLAG | CAN_SFF_MASK};
    }
    return setsockopt(l->fd, SOL_CAN_RAW, CAN_RAW_FILTER, f, (socklen_t)(n * (int)sizeof f[0]));
}

void link_close(tlink *l)
{
    if (l->fd >= 0)
        close(l->fd);
    l->fd = -1;
}

int link_listen_any(tlink *l, const proto_msg *msgs, int n)
{
    struct can_filter f[PM_COUNT];
    if (n > PM_COUNT)
        return -1;
    for (int i = 0; i < n; ++i) /* the function's bits, any node's */
        f[i] = (struct can_filter){(canid_t)(proto_table[msgs[i]].function << PROTO_NODE_BITS),
                                   CAN_EFF_FLAG | CAN_RTR_FLAG | (CAN_SFF_MASK & ~PROTO_NODE_MASK)};
    l->any_node = true;
    return setsockopt(l->fd, SOL_CAN_RAW, CAN_RAW_FILTER, f, (socklen_t)(n * (int)sizeof f[0]));
}

int link_send(tlink *l, proto_msg msg, const int32_t *values)
{
    return link_send_to(l, l->node, msg, values);
}

int link_send_to(tlink *l, uint8_t node, proto_msg msg, const int32_t *values)
{
    hal_can_frame f;
    if (proto_encode_values(msg, node, values, &f) != 0)
        return -1;
    struct can_frame fr;
    memset(&fr, 0, sizeof fr);
    fr.can_id = f.id;
    fr.can_dlc = f.len;
    memcpy(fr.data, f.data, f.len);
    /* A full interface queue (ENOBUFS: a burst, such as an update's blocks, outruns a real
     * adapter's queue) is waited out, a second at most. */
    for (int tries = 0; tries < 2000; ++tries) {
        if (write(l->fd, &fr, sizeof fr) == (ssize_t)sizeof fr)
            return 0;
        if (errno != ENOBUFS && errno != EAGAIN)
            return -1;
        const struct timespec half_ms = {0, 500000};
        nanosleep(&half_ms, NULL);
    }
    return -1;
}

static void heartbeat(tlink *l)
{
    const uint64_t now = link_now_us();
    if (!l->heartbeat || now < l->next_heartbeat_us)
        return;
    const int32_t v[1] = {l->hb_counter++};
    link_send(l, PM_HOST_HEARTBEAT, v);
    l->next_heartbeat_us = now + 100000u;
}

static void note_status(tlink *l, uint16_t counter)
{
    if (status_order_note(&l->statuses, counter) && !l->twin_warned) {
        l->twin_warned = true;
        fprintf(stderr,
                "tsectl: warning: two controllers seem to answer as node %u (their STATUS counters interleave): "
                "give each controller a node id of its own\n",
                l->node);
    }
}

int link_recv(tlink *l, proto_message *m, int timeout_ms)
{
    const uint64_t end = link_now_us() + (uint64_t)timeout_ms * 1000u;
    for (;;) {
        heartbeat(l);
        const uint64_t now = link_now_us();
        if (now >= end)
            return 0;
        uint64_t wait = (end - now) / 1000u;
        if (l->heartbeat && wait > 50)
            wait = 50;
        struct pollfd p = {l->fd, POLLIN, 0};
        const int r = poll(&p, 1, (int)wait + 1);
        if (r < 0)
            return errno == EINTR ? 0 : -1;
        if (r == 0)
            continue;
        struct can_frame fr;
        if (read(l->fd, &fr, sizeof fr) != (ssize_t)sizeof fr)
            continue;
        if (fr.can_id & (CAN_EFF_FLAG | CAN_RTR_FLAG | CAN_ERR_FLAG))
            continue;
        hal_can_frame f;
        f.id = (uint16_t)(fr.can_id & CAN_SFF_MASK);
        f.len = fr.can_dlc;
        memcpy(f.data, fr.data, 8);
        if (proto_decode(&f, PROTO_TO_HOST, m).reason == FW_REASON_NONE && (l->any_node || m->node == l->node)) {
            if (l->any_node)
                return 1;
            if (m->msg == PM_STATUS)
                note_status(l, (uint16_t)m->v[6]);
            if (m->msg == PM_TRAJ_END) {
                l->traj_end = *m;
                l->traj_end_seen = true;
            }
            return 1;
        }
        proto_message other;
        if (proto_decode(&f, PROTO_TO_CONTROLLER, &other).reason == FW_REASON_NONE && other.msg == PM_HOST_HEARTBEAT)
            l->other_heartbeat_us = link_now_us();
    }
}
