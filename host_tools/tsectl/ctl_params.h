/* The controller's parameter set, read over the bus one PARAM_GET at a time. */
#ifndef TSECTL_CTL_PARAMS_H
#define TSECTL_CTL_PARAMS_H

#include "fw/params.h"
#include "tsectl.h"

/* Reads parameter id.  Returns EXIT_OK with *value, or an exit status (a reject is printed). */
int ctl_param_get(tlink *l, int id, int32_t *value);

/* Reads the whole set.  Returns EXIT_OK or an exit status. */
int ctl_params_read(tlink *l, fw_param_set *s);

/* PARAM_SET of id to raw: its ACK, then its PARAM_VALUE.  Returns EXIT_OK with the value the
 * controller now holds in *now, EXIT_REJECTED with the REJECT in *reject (nothing printed), or
 * another exit status (said). */
int ctl_param_set(tlink *l, int id, int32_t raw, int32_t *now, proto_message *reject);

/* PARAM_SAVE: the set into the controller's non-volatile memory.  Returns an exit status (a
 * refusal printed). */
int ctl_params_save(tlink *l);

#endif
