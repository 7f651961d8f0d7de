#define _GNU_SOURCE
#include "hal_posix/posix_hal.h"

#include <errno.h>
#include <fcntl.h>
#include <linux/can.h>
#include <linux/can/error.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <unistd.h>

int posix_can_open(posix_can *c, const char *iface, uint8_t node)
{
    memset(c, 0, sizeof *c);
    atomic_init(&c->bus_off, false);
    atomic_init(&c->error_passive, false);
    atomic_init(&c->bus_off_events, 0u);
    atomic_init(&c->rx_overruns, 0u);
    c->fd = socket(PF_CAN, SOCK_RAW, CAN_RAW);
    if (c->fd < 0)
        return -1;
    struct ifreq ifr;
    memset(&ifr, 0, sizeof ifr);
    strncpy(ifr.ifr_name, iface, IFNAMSIZ - 1);
    if (ioctl(c->fd, SIOCGIFINDEX, &ifr) < 0)
        goto fail;
    /* Only our node and the broadcast node, standard frames only. */
    struct can_filter f[2] = {
        {node, CAN_EFF_FLAG | CAN_RTR_FLAG | 0x00F},
        {0, CAN_EFF_FLAG | CAN_RTR_FLAG | 0x00F},
    };
    if (setsockopt(c->fd, SOL_CAN_RAW, CAN_RAW_FILTER, f, sizeof f) < 0)
        goto fail;
    const can_err_mask_t err = CAN_ERR_BUSOFF | CAN_ERR_CRTL | CAN_ERR_RESTARTED;
    if (setsockopt(c->fd, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &err, sizeof err) < 0)
        goto fail;
    struct sockaddr_can addr;
    memset(&addr, 0, sizeof addr);
    addr.can_family = AF_CAN;
    addr.can_ifindex = ifr.ifr_ifindex;
    if (bind(c->fd, (struct sockaddr *)&addr, sizeof addr) < 0)
        goto fail;
    if (fcntl(c->fd, F_SETFL, O_NONBLOCK) < 0)
        goto fail;
    return 0;
fail:;
    const int e = errno;
    close(c->fd);
    c->fd = -1;
    errno = e;
    return -1;
}

void posix_can_close(posix_can *c)
{
    if (c->fd >= 0)
        close(c->fd);
    c->fd = -1;
}

static int can_send(void *ctx, const hal_can_frame *f)
{
    posix_can *c = ctx;
    struct can_frame fr;
    memset(&fr, 0, sizeof fr);
    fr.can_id = f->id & CAN_SFF_MASK;
    fr.can_dlc = f->len;
    memcpy(fr.data, f->data, f->len);
    return write(c->fd, &fr, sizeof fr) == (ssize_t)sizeof fr ? 0 : -1;
}

static int can_receive(void *ctx, hal_can_frame *f)
{
    posix_can *c = ctx;
    for (;;) {
        struct can_frame fr;
        const ssize_t n = read(c->fd, &fr, sizeof fr);
        if (n != (ssize_t)sizeof fr)
            return 0;
        if (fr.can_id & CAN_ERR_FLAG) {
            /* The count first: a tick that sees bus_off already sees the event. */
            if ((fr.can_id & CAN_ERR_BUSOFF) && !atomic_load(&c->bus_off)) {
                atomic_fetch_add(&c->bus_off_events, 1u);
                atomic_store(&c->bus_off, true);
            }
            if (fr.can_id & CAN_ERR_RESTARTED)
                atomic_store(&c->bus_off, false);
            if ((fr.can_id & CAN_ERR_CRTL) && (fr.data[1] & (CAN_ERR_CRTL_RX_PASSIVE | CAN_ERR_CRTL_TX_PASSIVE)))
                atomic_store(&c->error_passive, true);
            if ((fr.can_id & CAN_ERR_CRTL) && (fr.data[1] & CAN_ERR_CRTL_RX_OVERFLOW))
                atomic_fetch_add(&c->rx_overruns, 1u);
            continue;
        }
        if (fr.can_id & (CAN_EFF_FLAG | CAN_RTR_FLAG))
            continue;
        f->id = (uint16_t)(fr.can_id & CAN_SFF_MASK);
        f->len = fr.can_dlc > 8 ? 8 : fr.can_dlc;
        memcpy(f->data, fr.data, 8);
        return 1;
    }
}

static void can_state(void *ctx, hal_can_state *st)
{
    posix_can *c = ctx;
    memset(st, 0, sizeof *st);
    st->bus_off_events = atomic_load(&c->bus_off_events);
    st->bus_off = atomic_load(&c->bus_off);
    st->error_passive = atomic_load(&c->error_passive);
    st->rx_overruns = atomic_load(&c->rx_overruns);
}

hal_can posix_can_hal(posix_can *c)
{
    return (hal_can){c, can_send, can_receive, can_state};
}
