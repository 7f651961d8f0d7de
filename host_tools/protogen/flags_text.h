/* A field's meaning as protocol.md and the DBC print it: its doc, and for a field of bits each
 * bit's number, name and meaning from the table (proto_flag), so that they are written once. */
#ifndef PROTOGEN_FLAGS_TEXT_H
#define PROTOGEN_FLAGS_TEXT_H

#include <stddef.h>

#include "fw/proto_table.h"

/* Writes the meaning of message m's field k into buf (n bytes).  Returns 0, or -1 when it does not
 * fit, which it reports on stderr naming the field. */
int field_meaning(proto_msg m, int k, char *buf, size_t n);

#endif
