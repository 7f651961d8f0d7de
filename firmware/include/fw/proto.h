/* Frame codec driven by the wire table (fw/proto_wire.h).  The host's documentation table
 * (fw/proto_table.h) is declared with it for the host's code; the firmware uses none of it, and the
 * board image, which does not link it (tse_fw_doc), would fail to link if it did.
 *
 * A decoded frame is known good: its function exists and goes the expected way, its length is the
 * table's, and every field is inside the table's range.  Anything else is reported with the reason
 * (and the offending field) so that the controller can reject it without touching its state. */
#ifndef FW_PROTO_H
#define FW_PROTO_H

#include <stdint.h>

#include "fw/proto_table.h"
#include "fw/proto_wire.h"
#include "fw/types.h"
#include "hal/can.h"

typedef struct {
    proto_msg msg;
    uint8_t node;
    int32_t v[PROTO_MAX_FIELDS]; /* field values in table order (u32 fields hold 0..INT32_MAX) */
} proto_message;

typedef struct {
    fw_reason reason; /* FW_REASON_NONE when the frame decoded */
    uint8_t field;    /* offending field index, for FW_REASON_RANGE */
} proto_error;

/* The message of a function code in a direction, or PM_COUNT. */
proto_msg proto_find(uint8_t function, proto_direction dir);

uint16_t proto_id(proto_msg msg, uint8_t node);

/* Packs m.  Returns 0, or -1 when a value is outside its field's range or the node is > 15
 * (the frame is then left untouched). */
int proto_encode(const proto_message *m, hal_can_frame *f);

/* The same from msg's field values in table order (values holds its nfields) to node: what every
 * sender writes. */
int proto_encode_values(proto_msg msg, uint8_t node, const int32_t *values, hal_can_frame *f);

/* Unpacks a frame travelling in direction dir.  m->node is the node of the identifier. */
proto_error proto_decode(const hal_can_frame *f, proto_direction dir, proto_message *m);

#endif
