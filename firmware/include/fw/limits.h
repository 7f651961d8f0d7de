/* What a parameter set means for a controller of a given configuration: its geometry, the motion
 * limits planning and validation hold every path to, and the step generator's timing.
 *
 * One derivation, shared by the controller (fw_apply_params adopts exactly these) and by host
 * tools that must judge a path with the very limits the controller will (tsectl checking a
 * trajectory file offline).  Pure functions: no controller, no hardware. */
#ifndef FW_LIMITS_H
#define FW_LIMITS_H

#include <stdint.h>

#include "fw/move.h"
#include "fw/params.h"
#include "fw/stepgen.h"
#include "tse/geometry.h"

/* Planned slide motion keeps this much of the step generator's capacity in hand, for the
 * half-step rounding of each segment. */
#define FW_STEP_RATE_MARGIN TSE_R(0.9)

/* The step generator's timing for parameter set s at step_hz step interrupts and segment_hz
 * control segments per second: the STEP pulse and DIR set-up in whole ticks, and the spacing the
 * step rate limit asks for.  Returns 0, or -1 when the configuration is unusable (segment_hz zero
 * or not dividing step_hz) or s's pulse timing does not fit it (*sc is then unspecified). */
int fw_stepgen_config_from_params(const fw_param_set *s, uint32_t step_hz, uint32_t segment_hz,
                                  stepgen_config *sc);

/* The geometry and motion limits a controller with configuration (step_hz, segment_hz) derives
 * from parameter set s: what fw_apply_params adopts.  Returns 0, or -1 when s is refused (a
 * parameter out of range, an invalid geometry, or a pulse timing the configuration cannot give);
 * *g and *lim are then left untouched. */
int fw_limits_from_params(const fw_param_set *s, uint32_t step_hz, uint32_t segment_hz,
                          tse_geometry *g, fw_limits *lim);

#endif
