/* The codec's message table, made from the one list of messages (fw/proto_messages.def): numbers
 * only, each message's real fields and no more; the names and documentation are the host's
 * (fw/proto_table.h). */
#include "fw/proto_wire.h"

#include "fw/types.h"
#include "tse/status.h"

/* Each message's fields, an array of its own. */
#define PROTO_FIELD_DEF(seq, name, type, offset, min, max, unit, scale, values, doc) {min, max, type, offset, seq}
#define PROTO_MESSAGE(id, function, name, dir, dlc, fields, doc)                                   \
    static const proto_wire_field id##_fields[] = {fields};                                        \
    _Static_assert(sizeof id##_fields / sizeof id##_fields[0] <= PROTO_MAX_FIELDS, #id ": too many fields");
#include "fw/proto_messages.def"

#define PROTO_MESSAGE(id, function, name, dir, dlc, fields, doc)                                   \
    [id] = {id##_fields, function, dir, dlc, (uint8_t)(sizeof id##_fields / sizeof id##_fields[0])},
const proto_wire_msg proto_wire[PM_COUNT] = {
#include "fw/proto_messages.def"
};
