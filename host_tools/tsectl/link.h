/* tsectl's side of the bus: one raw SocketCAN socket, frames in and out through the firmware's
 * codec, host heartbeats while it waits. */
#ifndef TSECTL_LINK_H
#define TSECTL_LINK_H

#include <stdbool.h>
#include <stdint.h>

#include "fw/proto.h"

typedef struct {
    int fd;
    uint8_t node;
    uint64_t next_heartbeat_us;
    uint8_t hb_counter;
    bool heartbeat; /* send HOST_HEARTBEAT every 100 ms while waiting */
} tlink;

int link_open(tlink *l, const char *iface, uint8_t node);
void link_close(tlink *l);
uint64_t link_now_us(void);

/* Sends a message to the node.  Returns 0 or -1. */
int link_send(tlink *l, proto_msg msg, const int32_t *values);

/* Waits up to timeout_ms for a frame from the node that decodes as a host-bound message.
 * Returns 1 with *m filled, 0 on timeout, -1 on an error. */
int link_recv(tlink *l, proto_message *m, int timeout_ms);

#endif
