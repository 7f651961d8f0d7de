/* The parameter file that `tse-kin params` prints.
 *
 * Promise: every key tse-kin's parameter file takes, each once in its SI spelling, with the
 * prototype's value (the kinematic keys, exactly: the value reads back to the same double) or the
 * controller's default (the others, converted from fw_param_table's integer unit to SI), and its
 * unit, meaning and rule or range as a trailing comment; angles also in degrees in the comment.
 * kin_params_parse reads the text back to kin_params_default's values. */
#ifndef TSE_KIN_PARAMS_TEMPLATE_H
#define TSE_KIN_PARAMS_TEMPLATE_H

#include <stdio.h>

void kin_params_write_template(FILE *f);

#endif
