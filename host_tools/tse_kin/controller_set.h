/* The controller's whole parameter set for the commands that judge or plan motion (plan, check):
 * the defaults, or a parameter file as tse-sim and tsectl read it (param_text.h), where the motion
 * limits (slide_vmax, slide_amax, step_rate_max, ...) count too. */
#ifndef TSE_KIN_CONTROLLER_SET_H
#define TSE_KIN_CONTROLLER_SET_H

#include "commands.h"
#include "fw/params.h"

/* Fills *s from --params (or the defaults).  Returns KIN_EXIT_OK, or KIN_EXIT_FILE with the
 * reason on stderr. */
int kin_controller_set(const kin_run *run, fw_param_set *s);

/* The checks of plan's and check's command line (exactly one FILE) and bench's (nothing, or
 * 'plan' without --n). */
int cmd_one_file_check(const kin_options *o, char *err, size_t errlen);

#endif
