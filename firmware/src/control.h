/* The control tick's work, in its order: the e-stop completed, the command handed over taken,
 * supervision, the motion advanced, the state published. */
#ifndef FW_CONTROL_H
#define FW_CONTROL_H

#include "controller_internal.h"

void fw_control_run(fw_controller *c);

#endif
