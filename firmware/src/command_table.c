#include "fw/command_table.h"

#define A FW_REASON_NONE
#define S FW_REASON_STATE

/* Columns: boot, disabled, homing, idle, moving, stopping, fault, estop.  Motion commands check
 * homing and their queue on top of this. */
static const uint8_t allowed[PM_COUNT][FW_STATE_COUNT] = {
    [PM_ESTOP] = {A, A, A, A, A, A, A, A},
    [PM_STOP] = {S, A, A, A, A, A, A, A},
    [PM_HOST_HEARTBEAT] = {A, A, A, A, A, A, A, A},
    [PM_ENABLE] = {S, A, S, S, S, S, S, S},
    [PM_DISABLE] = {S, A, S, A, S, S, A, A},
    [PM_HOME] = {S, S, S, A, S, S, S, S},
    [PM_CLEAR_FAULT] = {S, S, S, S, S, S, A, A},
    [PM_POSE_A] = {S, A, A, A, A, A, A, A},
    [PM_POSE_B] = {S, A, A, A, A, A, A, A},
    [PM_POSE_C] = {S, A, A, A, A, A, A, A},
    [PM_MOVE_COMMIT] = {S, S, S, A, A, S, S, S},
    [PM_TRAJ_COMMIT] = {S, S, S, A, A, S, S, S},
    [PM_PARAM_GET] = {A, A, A, A, A, A, A, A},
    [PM_PARAM_SET] = {S, A, S, S, S, S, A, A},
    [PM_PARAM_SAVE] = {S, A, S, S, S, S, A, A},
    [PM_INFO_GET] = {A, A, A, A, A, A, A, A},
    /* Only with the drives off: the restart that follows drops them without a stop. */
    [PM_BOOT_ENTER] = {A, A, S, S, S, S, A, A},
    /* A bootloader's own commands: an application is in none of its states. */
    [PM_BOOT_QUERY] = {S, S, S, S, S, S, S, S},
    [PM_BOOT_ERASE] = {S, S, S, S, S, S, S, S},
    [PM_BOOT_WRITE] = {S, S, S, S, S, S, S, S},
    [PM_BOOT_VERIFY] = {S, S, S, S, S, S, S, S},
    [PM_BOOT_START] = {S, S, S, S, S, S, S, S},
    [PM_BOOT_DATA] = {S, S, S, S, S, S, S, S},
};

#undef A
#undef S

fw_reason fw_command_allowed(proto_msg cmd, fw_state state)
{
    if ((unsigned)cmd >= PM_COUNT || (unsigned)state >= FW_STATE_COUNT ||
        proto_wire[cmd].dir != PROTO_TO_CONTROLLER)
        return FW_REASON_UNKNOWN;
    return (fw_reason)allowed[cmd][state];
}
