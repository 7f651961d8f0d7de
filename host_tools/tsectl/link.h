/* tsectl's side of the bus: one raw SocketCAN socket, frames in and out through the firmware's
 * codec, host heartbeats while it waits. */
#ifndef TSECTL_LINK_H
#define TSECTL_LINK_H

#include <stdbool.h>
#include <stdint.h>

#include "fw/proto.h"
#include "status_order.h"

typedef struct {
    int fd;
    uint8_t node;
    uint64_t next_heartbeat_us;
    uint8_t hb_counter;
    bool heartbeat; /* send HOST_HEARTBEAT every 100 ms while waiting */
    /* What the bus shows beside our own traffic. */
    uint64_t other_heartbeat_us; /* when another host's HOST_HEARTBEAT to the node was last seen (0: never) */
    status_order statuses;       /* the node's STATUS counters (two controllers on one node id?) */
    bool twin_warned;            /* the warning of two controllers on one node id was given */
    /* link_recv takes any node's frames, not only the node's (a scan: link_listen_any). */
    bool any_node;
    /* The newest TRAJ_END read, whoever read it (a wait for rest reads on past it). */
    proto_message traj_end;
    bool traj_end_seen;
} tlink;

/* Opens the socket on the node's frames, telemetry (SLIDES, FK) excepted. */
int link_open(tlink *l, const char *iface, uint8_t node);
/* Telemetry through the socket's filter, or not.  Only while a command reads it: 120 frames a
 * second that nobody reads fill the socket's queue while tsectl computes (checking a path, on a
 * slow machine for seconds), and the answers that come next are then lost.  Returns 0 or -1. */
int link_telemetry(tlink *l, bool on);
void link_close(tlink *l);
uint64_t link_now_us(void);

/* Sends a message to the node, waiting up to a second while the interface's queue is full.
 * Returns 0 or -1. */
int link_send(tlink *l, proto_msg msg, const int32_t *values);
/* The same to another node. */
int link_send_to(tlink *l, uint8_t node, proto_msg msg, const int32_t *values);

/* The socket's filter on messages msgs[0..n-1] of every node, and link_recv taking any node's
 * (m->node says which), for a look over the whole bus; link_telemetry(l, false) and any_node =
 * false go back to the node alone.  Returns 0 or -1. */
int link_listen_any(tlink *l, const proto_msg *msgs, int n);

/* Waits up to timeout_ms for a frame from the node that decodes as a host-bound message.
 * Returns 1 with *m filled, 0 on timeout, -1 on an error.  Meanwhile it notes another host's
 * heartbeats to the node, and warns once on stderr when the node's STATUS counters show two
 * controllers answering under one node id. */
int link_recv(tlink *l, proto_message *m, int timeout_ms);

#endif
