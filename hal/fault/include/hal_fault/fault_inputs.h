/* A hal_inputs between the controller and the switches that forces inputs within windows of time:
 * the e-stop circuit open, or switches pressed (a slide's high-end limit hit, a homing switch
 * pressed where the slide is not).  Outside its windows it reads the inner inputs unchanged. */
#ifndef HAL_FAULT_INPUTS_H
#define HAL_FAULT_INPUTS_H

#include <stdint.h>

#include "hal/clock.h"
#include "hal/inputs.h"
#include "hal_fault/fault_time.h"

typedef struct {
    fault_window estop;  /* the e-stop circuit reads open */
    fault_window limit;  /* the switches of limit_mask read pressed */
    uint16_t limit_mask; /* bits as hal_inputs.limits: i slide i's homing switch, 8 + i its high end */
} fault_inputs_config;

typedef struct {
    fault_inputs_config cfg; /* may be changed between calls */
    hal_inputs inner;
    fault_clock clock;
} fault_inputs;

/* Wraps inner; the windows' time starts now on clock. */
void fault_inputs_init(fault_inputs *fi, const fault_inputs_config *cfg, hal_inputs inner, hal_clock clock);
hal_inputs fault_inputs_hal(fault_inputs *fi);

#endif
