/* The CAN message table: the single truth about the protocol.
 *
 * The codec (proto.c) packs and checks frames from it, host_tools/protogen prints docs/protocol.md
 * and docs/tse.dbc from it, and a test fails when those files differ from what the table says.
 *
 * Identifiers: id = function << 4 | node.  Nodes are 1..15; node 0 addresses every controller
 * (only e-stop and stop honour it).  A lower function code wins arbitration, so e-stop goes first.
 * Integers only, little-endian; every message has one fixed length. */
#ifndef FW_PROTO_TABLE_H
#define FW_PROTO_TABLE_H

#include <stdint.h>

#define PROTO_NODE_BITS 4
#define PROTO_NODE_MASK 0x0Fu
#define PROTO_BROADCAST 0u
#define PROTO_MAX_FIELDS 7

typedef enum { PROTO_TO_CONTROLLER, PROTO_TO_HOST } proto_direction;

typedef enum { PF_U8, PF_I8, PF_U16, PF_I16, PF_U24, PF_I24, PF_U32, PF_I32 } proto_field_type;

/* Named values of an enumerated field (for docs and the DBC's VAL_ table). */
typedef struct {
    int32_t value;
    const char *name;
} proto_enum_entry;

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

typedef enum {
    PM_ESTOP = 0,
    PM_STOP,
    PM_REJECT,
    PM_ACK,
    PM_HOST_HEARTBEAT,
    PM_ENABLE,
    PM_DISABLE,
    PM_HOME,
    PM_CLEAR_FAULT,
    PM_POSE_A,
    PM_POSE_B,
    PM_POSE_C,
    PM_MOVE_COMMIT,
    PM_TRAJ_COMMIT,
    PM_PARAM_GET,
    PM_PARAM_SET,
    PM_PARAM_SAVE,
    PM_STATUS,
    PM_SLIDES_A,
    PM_SLIDES_B,
    PM_SLIDES_C,
    PM_FK_A,
    PM_FK_B,
    PM_FK_C,
    PM_PARAM_VALUE,
    PM_MOVE_INFO,
    PM_COUNT
} proto_msg;

/* Fields in the order a row of proto_table.c reads (message, function code, name...); the
 * tightest order would save 8 bytes of flash a row, which the image does not need.
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

#endif
