/* The frames of the controller fuzz target read against docs/protocol.md's rules, here and not by
 * the codec under test: whom a frame addresses, whether a controller must answer it and why it
 * would be refused, and what a frame the controller sent says. */
#ifndef FUZZ_CONTROLLER_WIRE_H
#define FUZZ_CONTROLLER_WIRE_H

#include <stdbool.h>
#include <stdint.h>

#include "fw/proto_table.h"
#include "hal/can.h"

typedef enum {
    WIRE_OTHER_NODE,  /* for another controller: not ours */
    WIRE_OWN_TRAFFIC, /* a controller-to-host message (ours echoed, or another node's) */
    WIRE_BROADCAST,   /* node 0: only a well-formed ESTOP or STOP is honoured, nothing answers */
    WIRE_UNKNOWN,     /* to us, no such function: REJECT unknown */
    WIRE_BAD_LENGTH,  /* to us, a command of another length than the table's: REJECT bad_length */
    WIRE_RANGE,       /* to us, a field outside its range: REJECT range naming one such field */
    WIRE_COMMAND      /* to us, well-formed: answered as the command and the state say */
} wire_kind;

typedef struct {
    wire_kind kind;
    uint8_t function;
    proto_msg msg;             /* WIRE_BAD_LENGTH, WIRE_RANGE, WIRE_COMMAND and a well-formed broadcast */
    bool well_formed;          /* the length and every field as the table says */
    bool has_seq;
    uint8_t seq;               /* the sequence number, when the frame is well-formed or only a
                                * field other than it is out of range */
    int64_t v[PROTO_MAX_FIELDS];
    uint8_t bad_fields;        /* WIRE_RANGE: bit i, field i out of range */
} wire_frame;

/* How `node`'s controller must take frame f. */
void wire_classify(const hal_can_frame *f, uint8_t node, wire_frame *out);

/* Reads a frame the controller sent: it must be a controller-to-host message of node `node`, of
 * its table length, every field in range.  Returns the message, its values in *v. */
proto_msg wire_read_sent(const hal_can_frame *f, uint8_t node, int64_t v[PROTO_MAX_FIELDS]);

#endif
