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

#include "fw/types.h"

#define PROTO_NODE_BITS 4
#define PROTO_NODE_MASK 0x0Fu
#define PROTO_BROADCAST 0u
#define PROTO_MAX_FIELDS 7

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

/* A number of the table as text, for its documentation strings. */
#define PROTO_STR_(x) #x
#define PROTO_STR(x) PROTO_STR_(x)

typedef enum { PROTO_TO_CONTROLLER, PROTO_TO_HOST } proto_direction;

typedef enum { PF_U8, PF_I8, PF_U16, PF_I16, PF_U24, PF_I24, PF_U32, PF_I32 } proto_field_type;

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
    PM_INFO_GET,
    PM_STATUS,
    PM_SLIDES_A,
    PM_SLIDES_B,
    PM_SLIDES_C,
    PM_FK_A,
    PM_FK_B,
    PM_FK_C,
    PM_PARAM_VALUE,
    PM_MOVE_INFO,
    PM_TRAJ_END,
    PM_INFO,
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

#endif
