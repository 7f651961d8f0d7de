/* Which command each state accepts: one row per command message, one column per state
 * (command_table.c; docs/protocol.md prints it).  The thread refuses a command by it before any
 * work; the control tick judges it again against its own state when it takes the command, so a
 * state that changed in between refuses it too. */
#ifndef FW_COMMAND_TABLE_H
#define FW_COMMAND_TABLE_H

#include "fw/proto_wire.h"
#include "fw/types.h"

/* FW_REASON_NONE (accepted), FW_REASON_STATE, or FW_REASON_UNKNOWN for a message that is no
 * command. */
fw_reason fw_command_allowed(proto_msg cmd, fw_state state);

#endif
