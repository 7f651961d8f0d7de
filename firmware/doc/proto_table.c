/* The host's documentation table of the protocol (fw/proto_table.h), made from the list of messages
 * (fw/proto_messages.def), with the names of the values and bits its fields carry. */
#include "fw/proto_table.h"

#include <stddef.h>

#include "fw/types.h"
#include "tse/status.h"

const proto_enum_entry proto_state_names[] = {
    {FW_STATE_BOOT, "boot"},         {FW_STATE_DISABLED, "disabled"}, {FW_STATE_HOMING, "homing"},
    {FW_STATE_IDLE, "idle"},         {FW_STATE_MOVING, "moving"},     {FW_STATE_STOPPING, "stopping"},
    {FW_STATE_FAULT, "fault"},       {FW_STATE_ESTOP, "estop"},       {0, 0},
};

const proto_enum_entry proto_fault_names[] = {
    {FW_FAULT_NONE, "none"},
    {FW_FAULT_WATCHDOG, "watchdog"},
    {FW_FAULT_LIMIT, "limit"},
    {FW_FAULT_BUS_OFF, "bus_off"},
    {FW_FAULT_PLANNER, "planner"},
    {FW_FAULT_STEP_OVERRUN, "step_overrun"},
    {FW_FAULT_HOMING, "homing"},
    {FW_FAULT_ESTOP, "estop"},
    {FW_FAULT_UNDERRUN, "underrun"},
    {FW_FAULT_PLANT, "plant"},
    {FW_FAULT_HARDWARE, "hardware"},
    {0, 0},
};

const proto_enum_entry proto_reason_names[] = {
    {FW_REASON_NONE, "none"},
    {FW_REASON_BAD_LENGTH, "bad_length"},
    {FW_REASON_UNKNOWN, "unknown"},
    {FW_REASON_RANGE, "range"},
    {FW_REASON_STATE, "state"},
    {FW_REASON_NOT_HOMED, "not_homed"},
    {FW_REASON_INCOMPLETE, "incomplete"},
    {FW_REASON_STALE, "stale"},
    {FW_REASON_KINEMATICS, "kinematics"},
    {FW_REASON_QUEUE_FULL, "queue_full"},
    {FW_REASON_PARAM_UNKNOWN, "param_unknown"},
    {FW_REASON_PARAM_RANGE, "param_range"},
    {FW_REASON_PARAM_SET, "param_set"},
    {FW_REASON_STORAGE, "storage"},
    {FW_REASON_TIMING, "timing"},
    {FW_REASON_ORDER, "order"},
    {FW_REASON_ENDED, "ended"},
    {FW_REASON_TOO_LONG, "too_long"},
    {FW_REASON_CRC, "crc"},
    {FW_REASON_ADDRESS, "address"},
    {FW_REASON_LENGTH, "length"},
    {FW_REASON_HEADER, "header"},
    {FW_REASON_BOARD, "board"},
    {FW_REASON_FLASH, "flash"},
    {FW_REASON_NO_IMAGE, "no_image"},
    {0, 0},
};

const proto_enum_entry proto_kin_status_names[] = {
    {TSE_OK, "ok"},           {TSE_INVALID, "invalid"},   {TSE_UNREACHABLE, "unreachable"},
    {TSE_BELOW, "below"},     {TSE_ALPHA, "alpha"},       {TSE_STROKE, "stroke"},
    {TSE_SINGULAR, "singular"}, {TSE_DEGENERATE, "degenerate"}, {TSE_NOCONVERGE, "noconverge"},
    {0, 0},
};

const proto_enum_entry proto_move_kind_names[] = {
    {0, "duration"},
    {1, "speed"},
    {0, 0},
};

const proto_enum_entry proto_move_start_names[] = {
    {FW_START_REST, "rest"},
    {FW_START_BLENDED, "blended"},
    {FW_START_AFTER, "after"},
    {0, 0},
};

const proto_enum_entry proto_move_bound_names[] = {
    {FW_BOUND_ASKED, "asked"},
    {FW_BOUND_PLATE_VMAX, "plate_vmax"},
    {FW_BOUND_PLATE_AMAX, "plate_amax"},
    {FW_BOUND_PLATE_JMAX, "plate_jmax"},
    {FW_BOUND_PLATE_WMAX, "plate_wmax"},
    {FW_BOUND_PLATE_DWMAX, "plate_dwmax"},
    {FW_BOUND_PLATE_JMAX_ANGULAR, "plate_jmax_angular"},
    {FW_BOUND_SLIDE_VMAX, "slide_vmax"},
    {FW_BOUND_SLIDE_AMAX, "slide_amax"},
    {FW_BOUND_STEP_GENERATOR, "step_generator"},
    {0, 0},
};

const proto_enum_entry proto_traj_end_names[] = {
    {FW_TRAJ_END_NONE, "none"},
    {FW_TRAJ_END_DONE, "done"},
    {FW_TRAJ_END_STOP, "stop"},
    {FW_TRAJ_END_FAULT, "fault"},
    {0, 0},
};

const proto_flag proto_status_flags[] = {
    {PROTO_STATUS_HOMED, "homed", "homed"},
    {PROTO_STATUS_DRIVES, "drives", "drives enabled"},
    {PROTO_STATUS_ESTOP_IN, "estop_in", "e-stop input open"},
    {PROTO_STATUS_SWITCHES_OFF, "switches_off",
     "a high-end switch pressed or (once homed) a homing switch disagreeing with the step count"},
    {PROTO_STATUS_ERROR_PASSIVE, "error_passive", "CAN error passive"},
    {0, 0, 0},
};

const proto_flag proto_traj_flags[] = {
    {PROTO_TRAJ_LAST, "last", "the trajectory's last row"},
    {PROTO_TRAJ_FIRST, "first", "its first row, which starts it"},
    {0, 0, 0},
};

const proto_flag_field proto_flag_fields[] = {
    {PM_STATUS, 2, proto_status_flags},
    {PM_TRAJ_COMMIT, 2, proto_traj_flags},
    {PM_COUNT, 0, 0},
};

const proto_flag *proto_field_flags(proto_msg m, int k)
{
    for (const proto_flag_field *f = proto_flag_fields; f->flags; ++f)
        if (f->msg == m && f->field == k)
            return f->flags;
    return 0;
}

const proto_enum_def proto_enums[] = {
    {proto_state_names, "state", "state"},
    {proto_fault_names, "fault", "fault"},
    {proto_reason_names, "reason", "reject reason"},
    {proto_kin_status_names, "kin_status", "kinematic status (kinematics.md)"},
    {proto_move_kind_names, "move_kind", "move kind"},
    {proto_move_start_names, "move_start", "move start"},
    {proto_move_bound_names, "move_bound", "move bound"},
    {proto_traj_end_names, "traj_end", "trajectory end (`TRAJ_END.ended`, `REJECT` `ended`)"},
    {0, 0, 0},
};

/* Each message's row with everything the list says of it; nfields counts its fields. */
#define PROTO_FIELD_DEF(seq, name, type, offset, min, max, unit, scale, values, doc)                \
    {name, type, offset, min, max, unit, scale, values, doc}
#define PROTO_MESSAGE(id, function, name, dir, dlc, fields, doc)                                   \
    {id, function, name, dir, dlc, (uint8_t)(sizeof (proto_field[]){fields} / sizeof(proto_field)), {fields}, doc},
const proto_def proto_table[PM_COUNT] = {
#include "fw/proto_messages.def"
};

const proto_def *proto_lookup(uint8_t function, proto_direction dir)
{
    for (int i = 0; i < PM_COUNT; ++i)
        if (proto_table[i].function == function && proto_table[i].dir == dir)
            return &proto_table[i];
    return NULL;
}

const char *proto_enum_name(const proto_enum_entry *table, int32_t value)
{
    for (const proto_enum_entry *e = table; e && e->name; ++e)
        if (e->value == value)
            return e->name;
    return "?";
}

const char *proto_code_words(const proto_code *table, int32_t value)
{
    for (const proto_code *c = table; c && c->name; ++c)
        if (c->value == value)
            return c->words;
    return NULL;
}
