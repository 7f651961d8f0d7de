/* The CAN message table as people read it: the host's documentation table.
 *
 * Made, like the codec's wire table (fw/proto_wire.h), from the one list of messages
 * (fw/proto_messages.def), with everything the list says: names, units, scales, the names of
 * enumerated values and of flag bits, the codes REJECT carries and their words, and the
 * documentation.  host_tools/protogen prints docs/protocol.md, docs/tse_node1.dbc and
 * python/tse/_protocol.py from it, and a test fails when those files differ from what it says;
 * tsectl, tse-sim, tse.can and the tests name what they send and read with it.
 *
 * It lives in the library tse_fw_doc (firmware/doc/), which host programs get with the firmware's
 * library and the board image does not link: the firmware itself uses the wire table only. */
#ifndef FW_PROTO_TABLE_H
#define FW_PROTO_TABLE_H

#include <stdint.h>

#include "fw/proto_wire.h"
#include "fw/types.h"

/* Named values of an enumerated field (for docs and the DBC's VAL_ table). */
typedef struct {
    int32_t value;
    const char *name;
} proto_enum_entry;

/* Codes a field carries for one reason, each with its words (what tsectl and tse.can say): the
 * limit a timing refusal names and the rule a param_set refusal names.  Terminated by a NULL
 * name. */
typedef struct {
    int32_t value;
    const char *name;
    const char *words;
} proto_code;

/* The bits of a flags field: mask, name, meaning.  Terminated by a NULL name. */
typedef struct {
    uint32_t mask;
    const char *name;
    const char *doc;
} proto_flag;

typedef struct {
    const char *name;
    proto_field_type type;
    uint8_t offset;      /* first byte */
    int32_t min, max;    /* accepted raw range (a frame outside it is rejected) */
    const char *unit;    /* physical unit after scaling ("" if none) */
    double scale;        /* physical = raw * scale; for the DBC and the docs only */
    const proto_enum_entry *values; /* NULL-terminated names, or NULL */
    const char *doc;
} proto_field;

/* Fields in the order a message of fw/proto_messages.def reads (message, function code, name...);
 * a host table, its padding of no account.
 * NOLINTNEXTLINE(clang-analyzer-optin.performance.Padding) */
typedef struct {
    proto_msg msg;
    uint8_t function;    /* id >> 4 */
    const char *name;
    proto_direction dir;
    uint8_t dlc;
    uint8_t nfields;
    proto_field fields[PROTO_MAX_FIELDS];
    const char *doc;
} proto_def;

extern const proto_def proto_table[PM_COUNT];

/* The table entry of a function code in a direction, or NULL. */
const proto_def *proto_lookup(uint8_t function, proto_direction dir);

/* Name of a value of an enumeration table, or "?". */
const char *proto_enum_name(const proto_enum_entry *table, int32_t value);

/* Enumerations that travel on the wire (shared with docs and DBC). */
extern const proto_enum_entry proto_state_names[];
extern const proto_enum_entry proto_fault_names[];
extern const proto_enum_entry proto_reason_names[];
extern const proto_enum_entry proto_kin_status_names[];
extern const proto_enum_entry proto_move_kind_names[];
extern const proto_enum_entry proto_move_start_names[];
extern const proto_enum_entry proto_move_bound_names[];

/* Every enumeration above, with the key the Python tables give it and the title the protocol
 * document gives it; ends with a NULL table. */
typedef struct {
    const proto_enum_entry *table;
    const char *key;
    const char *title;
} proto_enum_def;
extern const proto_enum_def proto_enums[];

/* The fields of bits, each with its bits.  Terminated by a NULL flags. */
typedef struct {
    proto_msg msg;
    int field;
    const proto_flag *flags;
} proto_flag_field;
extern const proto_flag proto_status_flags[];
extern const proto_flag proto_traj_flags[];
extern const proto_flag_field proto_flag_fields[];

/* The bits of message m's field k, or NULL when it is not a field of bits. */
const proto_flag *proto_field_flags(proto_msg m, int k);
extern const proto_enum_entry proto_traj_end_names[];

/* REJECT's field for timing, divided by 16 (fw_slide_limit): the limit the demand is against. */
extern const proto_code proto_slide_limits[];
/* REJECT's where for param_set (fw_param_rule): the rule the set breaks. */
extern const proto_code proto_param_rules[];

/* Every code table above, with the key the Python tables give it and the title the protocol
 * document gives it; ends with a NULL table. */
typedef struct {
    const proto_code *table;
    const char *key;
    const char *title;
} proto_code_def;
extern const proto_code_def proto_code_tables[];

/* Words of a code of a code table, or NULL for a value it does not have. */
const char *proto_code_words(const proto_code *table, int32_t value);

#endif
