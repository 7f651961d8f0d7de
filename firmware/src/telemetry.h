/* The thread's periodic frames: STATUS every status_ms, and the slides and the plate's pose
 * (forward kinematics of the steps emitted) every telemetry_ms, from the view. */
#ifndef FW_TELEMETRY_H
#define FW_TELEMETRY_H

#include "controller_internal.h"

/* Sends what is due, from the view the thread last read (c->th.view). */
void fw_telemetry_poll(fw_controller *c);

/* The same from a view of its own, for a look at the bus in the middle of a validation
 * (fw/work.h): the validation plans from c->th.view, which must not change under it, while the
 * host goes on hearing STATUS and telemetry at their periods however long the validation takes. */
void fw_telemetry_look(fw_controller *c);

#endif
