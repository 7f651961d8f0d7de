/* The pose the controller reports from its slides, judged by the double-precision kinematics
 * (fk_oracle.h): in the float build that is the board's arithmetic against an independent one. */
#ifndef FUZZ_CONTROLLER_FK_CHECK_H
#define FUZZ_CONTROLLER_FK_CHECK_H

#include <stdint.h>

#include "oracle_model.h"

/* A SLIDES or FK frame of a telemetry burst (m: PM_SLIDES_A.. or PM_FK_A..; v: its fields). */
void fk_check_frame(oracle_model *o, rig *r, proto_msg m, const int64_t *v);

/* The burst is over (the outputs were read): judges it. */
void fk_check_burst(oracle_model *o, rig *r);

#endif
