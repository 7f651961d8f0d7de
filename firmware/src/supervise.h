/* The control tick's supervision: the e-stop input, the switches against the step count, the
 * bus, the step generator's overruns and the host's heartbeat, each a fault when it says so; and
 * what STATUS reports of them, kept for the view. */
#ifndef FW_SUPERVISE_H
#define FW_SUPERVISE_H

#include "controller_internal.h"

void fw_supervise(fw_controller *c);

#endif
