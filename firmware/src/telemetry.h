/* The thread's periodic frames: STATUS every status_ms, and the slides and the plate's pose
 * (forward kinematics of the steps emitted) every telemetry_ms, from the view. */
#ifndef FW_TELEMETRY_H
#define FW_TELEMETRY_H

#include "controller_internal.h"

/* Sends what is due. */
void fw_telemetry_poll(fw_controller *c);

#endif
