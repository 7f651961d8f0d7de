/* The CAN protocol as the codec needs it: identifiers, the wire's units and ranges, and the wire
 * table (each message's function code, direction, length and fields: type, first byte, raw range).
 *
 * The messages are written once, in fw/proto_messages.def; this table and the host's documentation
 * table (fw/proto_table.h: names, units, scales, value names, docs; protogen prints docs/protocol.md,
 * docs/tse_node1.dbc and python/tse/_protocol.py from it) are both made from that list, so the board
 * image carries the wire table alone (tests/firmware/test_proto.c holds the two equal).
 *
 * Identifiers: id = function << 4 | node.  Nodes are 1..15; node 0 addresses every controller
 * (only e-stop and stop honour it).  A lower function code wins arbitration, so e-stop goes first.
 * Integers only, little-endian; every message has one fixed length. */
#ifndef FW_PROTO_WIRE_H
#define FW_PROTO_WIRE_H

#include <stdint.h>

#include "fw/types.h"

#define PROTO_NODE_BITS 4
#define PROTO_NODE_MASK 0x0Fu
#define PROTO_BROADCAST 0u
#define PROTO_MAX_FIELDS 8

/* STATUS's flags, one bit each; proto_status_flags names and documents them (docs/protocol.md,
 * the DBC and the Python tables are written from it). */
#define PROTO_STATUS_HOMED 0x01u
#define PROTO_STATUS_DRIVES 0x02u
#define PROTO_STATUS_ESTOP_IN 0x04u
#define PROTO_STATUS_SWITCHES_OFF 0x08u
#define PROTO_STATUS_ERROR_PASSIVE 0x10u

/* TRAJ_COMMIT's flags; proto_traj_flags names and documents them, as proto_status_flags does
 * STATUS's. */
#define PROTO_TRAJ_LAST 1u  /* the trajectory's last row */
#define PROTO_TRAJ_FIRST 2u /* its first row: starts it */

/* Trajectory rows a host keeps in flight (sent, their ACK or REJECT not yet read) while it
 * streams, within the queue's free slots: 4 rows are 16 frames, half the board's 32-frame receive
 * ring (hal/stm32f4 can_ring.h), so a burst fits while the controller validates a row; and enough
 * that the bus's and the host's round trip no longer sets the pace (docs/protocol.md). */
#define PROTO_TRAJ_WINDOW 4

/* REJECT's field for a timing refusal: the slide (1..6) plus this times the slide limit's code
 * (proto_slide_limit_names). */
#define PROTO_REJECT_LIMIT_STRIDE 16

/* The wire's units, raw counts per SI unit, and its ranges, written once: the table's scales and
 * ranges are made of them, and every conversion between SI and the wire (on the board, in the host
 * tools, and in Python, whose _protocol.py protogen prints them into) is written with them.
 * Parameters travel in the units of the parameter table (fw/params.h), micro-units among them. */
#define PROTO_UM_PER_M 1000000      /* a pose's x, y, z in um; a parameter's lengths and speeds */
#define PROTO_URAD_PER_RAD 1000000  /* a pose's angles in urad */
#define PROTO_NM_PER_M 1000000000   /* SLIDES' slide positions in nm */
#define PROTO_US_PER_S 1000000      /* TRAJ_COMMIT's dt in us */
#define PROTO_MS_PER_S 1000         /* MOVE_COMMIT's duration, MOVE_INFO's times in ms */
#define PROTO_PER_MILLE 1000        /* REJECT's where and MOVE_INFO's demand: thousandths */
#define PROTO_POS_MAX_UM 4000000    /* a pose's |x|, |y|, |z| at most 4 m */
#define PROTO_ANGLE_MAX_URAD 3141593 /* a pose's angles within +-pi */
#define PROTO_DT_MIN_US 1000        /* a trajectory row's dt: 1 ms ... */
#define PROTO_DT_MAX_US 60000000    /* ... to 60 s */
/* MOVE_COMMIT's value: at most FW_MOVE_MAX_S in ms for a duration, the same count of um/s (3.6 m/s)
 * for a speed; at least 1. */
#define PROTO_MOVE_VALUE_MAX (FW_MOVE_MAX_S * PROTO_MS_PER_S)

/* Raw units per SI unit of a pose's coordinate k: x, y, z (0..2) in um, the angles in urad. */
static inline int32_t proto_pose_units(int k)
{
    /* The same count today, of different units: each named for what it counts.
     * NOLINTNEXTLINE(bugprone-branch-clone) */
    return k < 3 ? PROTO_UM_PER_M : PROTO_URAD_PER_RAD;
}

typedef enum { PROTO_TO_CONTROLLER, PROTO_TO_HOST } proto_direction;

typedef enum { PF_U8, PF_I8, PF_U16, PF_I16, PF_U24, PF_I24, PF_U32, PF_I32 } proto_field_type;

/* The messages, PM_ESTOP = 0 ... in the order of fw/proto_messages.def. */
typedef enum {
#define PROTO_MESSAGE(id, function, name, dir, dlc, fields, doc) id,
#include "fw/proto_messages.def"
    PM_COUNT
} proto_msg;

/* A field as the codec packs and checks it. */
typedef struct {
    int32_t min, max; /* accepted raw range (a frame outside it is rejected) */
    uint8_t type;     /* proto_field_type */
    uint8_t offset;   /* first byte */
    uint8_t seq;      /* 1: a sequence number (a field named "seq"; a command's first, echoed) */
} proto_wire_field;

typedef struct {
    const proto_wire_field *fields; /* nfields of them, in table order */
    uint8_t function;               /* id >> 4 */
    uint8_t dir;                    /* proto_direction */
    uint8_t dlc;
    uint8_t nfields;
} proto_wire_msg;

extern const proto_wire_msg proto_wire[PM_COUNT];

#endif
