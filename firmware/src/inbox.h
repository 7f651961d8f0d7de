/* The thread's frames in: the bus, and the frames a validation took off it meanwhile.
 *
 * While a long validation runs (fw/work.h), the thread looks at the bus between its pieces: it
 * moves the frames waiting into the inbox (up to FW_INBOX; the rest wait on the bus), takes a
 * heartbeat to this controller at once (it needs no answer), halts stepping at once on an ESTOP
 * (fw_estop_halt: the tick completes it), and ends the validation on an ESTOP, or on a STOP while
 * the robot moves (the commit is then refused `state`, and the stop answered right after), and
 * sends STATUS and telemetry when they are due (fw_telemetry_look).  Every other frame waits in
 * the inbox, in order, for the validation's answer. */
#ifndef FW_INBOX_H
#define FW_INBOX_H

#include <stdbool.h>

#include "controller_internal.h"

/* The next frame: the inbox's oldest, else the bus's.  Returns false when none waits. */
bool fw_inbox_next(fw_controller *c, hal_can_frame *f);

/* The bus's next frame; when none waits, the time of the look is kept as when the thread last found
 * the bus empty (fw_shared.bus_read_us, what the watchdog judges silence by).  Every read of the
 * bus goes through here. */
bool fw_inbox_receive(fw_controller *c, hal_can_frame *f);

/* Validation under way (fw/work.h), watched as above; moving: a STOP ends it too. */
void fw_inbox_watch_begin(fw_controller *c, bool moving);
/* Its end: true when a STOP or an ESTOP ended it (or came while it ran, for a motion). */
bool fw_inbox_watch_end(fw_controller *c);

/* One look at the bus as above, outside a validation: while the thread waits for the control tick
 * to take a command (fw/runtime.h), heartbeats are taken and an ESTOP halts stepping meanwhile. */
void fw_inbox_look(fw_controller *c);

/* The oldest STOP or ESTOP in the inbox, taken out of it (the one that ended a validation, answered
 * before the frames ahead of it).  Returns false when there is none. */
bool fw_inbox_take_stop(fw_controller *c, hal_can_frame *f);

#endif
