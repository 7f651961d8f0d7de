/* The thread's command handling: a frame decoded, authorised by the state table against the view,
 * then what it asks prepared (a move planned, a row validated, a parameter set judged) and handed to
 * the control tick, whose verdict is answered.  Every refused command gets a REJECT naming why, and
 * nothing of it is applied. */
#ifndef FW_COMMANDS_H
#define FW_COMMANDS_H

#include "controller_internal.h"

void fw_handle_frame(fw_controller *c, const hal_can_frame *f);

#endif
