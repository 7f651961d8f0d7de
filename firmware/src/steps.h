/* Slide positions in steps, from a parameter set's step size and switch positions. */
#ifndef FW_STEPS_H
#define FW_STEPS_H

#include <stdint.h>

#include "fw/params.h"
#include "tse/real.h"

/* Steps of a slide position [m], rounded to the nearest. */
int32_t fw_steps_of(const fw_param_set *p, tse_real s);

/* Whole steps of a length in micrometres (integer: the same on the float board build). */
int32_t fw_steps_of_um(const fw_param_set *p, int32_t um);

/* Slide k's homing switch position (home_sw_k) in steps: the last whole step at which it is
 * pressed, rounded down (the release edge is the step above). */
int32_t fw_switch_steps(const fw_param_set *p, int k);

#endif
