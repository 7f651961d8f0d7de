/* A parameter set: judged and prepared for this controller's rates (the thread, fw_init), then
 * adopted by the control tick at rest (the step generator restarted on the new timing, the zero
 * dropped when the geometry, the stroke, a switch or the step size changed). */
#ifndef FW_ADOPT_H
#define FW_ADOPT_H

#include "controller_internal.h"

/* FW_RULE_NONE with *p filled, or the rule set s breaks at the controller's rates (fw/limits.h). */
fw_param_rule fw_params_prepare(const fw_controller *c, const fw_param_set *s, fw_prepared_params *p);

/* Adopts a prepared set: FW_RULE_NONE, or FW_RULE_NOT_AT_REST (the step generator still runs;
 * nothing changes then).  The tick's context, or fw_init. */
fw_param_rule fw_params_adopt(fw_controller *c, const fw_prepared_params *p);

#endif
