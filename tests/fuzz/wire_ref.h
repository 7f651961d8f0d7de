/* The wire format read from docs/protocol.md's rules, for the fuzz targets that judge the codec and
 * the controller: written here, not taken from firmware/src/proto.c, so that a fault there cannot
 * hide itself.  Only the message table (the data under test's description) is shared. */
#ifndef TESTS_FUZZ_WIRE_REF_H
#define TESTS_FUZZ_WIRE_REF_H

#include <stdint.h>

#include "fw/proto_table.h"

/* A field's value from a frame's data bytes: little-endian, two's complement of its width. */
int64_t wire_ref_field(const uint8_t *data, const proto_field *fd);

/* The table's entry for a function code travelling in direction dir, or NULL. */
const proto_def *wire_ref_entry(uint8_t function, proto_direction dir);

#endif
