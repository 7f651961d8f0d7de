/* The control tick's state machine: the drives, faults (a controlled stop first when anything
 * moves, then latched), the emergency stop, and the commands that change state at rest. */
#ifndef FW_STATE_H
#define FW_STATE_H

#include <stdbool.h>

#include "controller_internal.h"

/* The drives on or off (an e-stop request meanwhile keeps them off). */
void fw_drives(fw_controller *c, bool on);

/* The e-stop's first half, from any context (an interrupt, the thread reading an ESTOP frame):
 * stepping halts, the drives go off, the tick is asked to complete it. */
void fw_estop_halt(fw_controller *c);

/* The e-stop's second half (the tick): every setpoint dropped, state ESTOP, the zero dropped. */
void fw_estop(fw_controller *c);

/* Completes a pending fw_estop_halt with fw_estop (nothing if none is pending). */
void fw_estop_complete(fw_controller *c);

/* A fault: a controlled stop first when anything moves, then latched. */
void fw_fault_raise(fw_controller *c, fw_fault f);

/* Motion came to rest (fw_motion_tick): the pending fault latches, or the state is IDLE. */
void fw_state_at_rest(fw_controller *c);

/* ENABLE, DISABLE, CLEAR_FAULT, the state table having allowed them: FW_REASON_NONE, or
 * FW_REASON_STATE (CLEAR_FAULT with the e-stop input still open). */
fw_reason fw_state_enable(fw_controller *c);
fw_reason fw_state_disable(fw_controller *c);
fw_reason fw_state_clear(fw_controller *c);

#endif
