/* tse-canbridge: carries CAN frames between a SocketCAN interface and the emulated board's CAN
 * channel (can_record.h: a UNIX socket the emulator serves, or the VM's virtio port that leads to
 * it), both ways, until the channel closes or a signal ends it.  It is the board's link to the
 * bus in the vcan harness (tests/vcan/harness.sh --board), so that tsectl, tse.can and can-utils
 * reach the emulated board on vcan0 as they reach tse-sim.
 *
 *   tse-canbridge --channel PATH --iface IF
 *
 * A record the channel should not carry is dropped with a warning naming what was wrong; error
 * frames on the interface are not carried (the emulated bus makes its own).  At the end it prints
 * how many frames went each way. */
#define _GNU_SOURCE
#include <errno.h>
#include <linux/can.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <unistd.h>

#include "can_record.h"
#include "endpoint.h"

static volatile sig_atomic_t stop;

static void on_signal(int s)
{
    (void)s;
    stop = 1;
}

static int can_open(const char *iface)
{
    const int fd = socket(PF_CAN, SOCK_RAW, CAN_RAW);
    if (fd < 0)
        return -1;
    struct ifreq ifr;
    memset(&ifr, 0, sizeof ifr);
    strncpy(ifr.ifr_name, iface, IFNAMSIZ - 1);
    struct sockaddr_can a;
    memset(&a, 0, sizeof a);
    a.can_family = AF_CAN;
    if (ioctl(fd, SIOCGIFINDEX, &ifr) < 0)
        goto fail;
    a.can_ifindex = ifr.ifr_ifindex;
    if (bind(fd, (struct sockaddr *)&a, sizeof a) < 0)
        goto fail;
    return fd;
fail:;
    const int e = errno;
    close(fd);
    errno = e;
    return -1;
}

static int usage(void)
{
    fprintf(stderr, "usage: tse-canbridge --channel PATH --iface IF\n"
                    "Carries CAN frames between interface IF and the emulated board's CAN channel PATH\n"
                    "(a UNIX socket, or a character device leading to one): docs/emulator.md.\n");
    return 2;
}

int main(int argc, char **argv)
{
    const char *channel = NULL, *iface = NULL;
    for (int i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--channel") && i + 1 < argc)
            channel = argv[++i];
        else if (!strcmp(argv[i], "--iface") && i + 1 < argc)
            iface = argv[++i];
        else if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h"))
            return usage(), 0;
        else
            return fprintf(stderr, "tse-canbridge: unexpected argument '%s'\n", argv[i]), usage();
    }
    if (!channel || !iface)
        return fprintf(stderr, "tse-canbridge: --channel and --iface are needed\n"), usage();
    const int ch = endpoint_open(channel);
    if (ch < 0)
        return fprintf(stderr, "tse-canbridge: cannot open the channel %s: %s\n", channel, strerror(errno)), 1;
    const int bus = can_open(iface);
    if (bus < 0)
        return fprintf(stderr, "tse-canbridge: cannot open CAN interface %s: %s\n", iface, strerror(errno)), 1;
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);

    uint8_t rec[CAN_RECORD_SIZE];
    size_t have = 0;
    unsigned long to_bus = 0, to_board = 0, bad = 0;
    int rc = 0;
    while (!stop) {
        struct pollfd p[2] = {{ch, POLLIN, 0}, {bus, POLLIN, 0}};
        if (poll(p, 2, 200) < 0) {
            if (errno == EINTR)
                continue;
            rc = 1;
            break;
        }
        if (p[0].revents & (POLLIN | POLLHUP | POLLERR)) {
            const ssize_t n = read(ch, rec + have, sizeof rec - have);
            if (n == 0 || (n < 0 && errno != EINTR && errno != EAGAIN)) {
                fprintf(stderr, "tse-canbridge: the channel %s closed\n", channel);
                break;
            }
            if (n > 0 && (have += (size_t)n) == sizeof rec) {
                have = 0;
                can_record r;
                const char *why = NULL;
                if (can_record_unpack(rec, &r, &why) != 0) {
                    ++bad;
                    fprintf(stderr, "tse-canbridge: dropped a record from the board: %s\n", why);
                } else {
                    struct can_frame f;
                    memset(&f, 0, sizeof f);
                    f.can_id = r.can_id;
                    f.can_dlc = r.len;
                    memcpy(f.data, r.data, r.len);
                    /* A full transmit queue (ENOBUFS) drains within a frame time: try again. */
                    for (int tries = 0; tries < 100; ++tries) {
                        if (write(bus, &f, sizeof f) == (ssize_t)sizeof f) {
                            ++to_bus;
                            break;
                        }
                        if (errno != ENOBUFS && errno != EAGAIN && errno != EINTR)
                            break;
                        usleep(1000);
                    }
                }
            }
        }
        if (p[1].revents & POLLIN) {
            struct can_frame f;
            if (read(bus, &f, sizeof f) == (ssize_t)sizeof f && !(f.can_id & CAN_ERR_FLAG)) {
                can_record r = {f.can_id, f.can_dlc > 8 ? 8 : f.can_dlc, {0}};
                memcpy(r.data, f.data, r.len);
                uint8_t out[CAN_RECORD_SIZE];
                can_record_pack(&r, out);
                if (endpoint_write_all(ch, out, sizeof out) != 0) {
                    fprintf(stderr, "tse-canbridge: cannot write to the channel %s: %s\n", channel, strerror(errno));
                    rc = 1;
                    break;
                }
                ++to_board;
            }
        }
    }
    fprintf(stderr, "tse-canbridge: %lu frames to the bus, %lu to the board, %lu records dropped\n", to_bus, to_board,
            bad);
    close(bus);
    close(ch);
    return rc;
}
