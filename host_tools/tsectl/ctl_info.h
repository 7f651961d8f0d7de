/* What the controller is (INFO_GET page 0, docs/protocol.md): its firmware's version and the rates
 * it runs at, which a path or a parameter set is judged at. */
#ifndef TSECTL_CTL_INFO_H
#define TSECTL_CTL_INFO_H

#include <stdbool.h>

#include "fw/limits.h"
#include "tsectl.h"

typedef struct {
    int major, minor, patch;
    fw_rates rates;
} ctl_info;

/* Reads INFO.  Returns EXIT_OK with *info, or an exit status: EXIT_REJECTED with *older set (nothing
 * said) when the controller does not know INFO_GET (REJECT unknown: a firmware older than INFO),
 * any other failure said. */
int ctl_info_read(tlink *l, ctl_info *info, bool *older);

/* The rates to judge node's paths and sets at: its INFO's.  A controller that does not know
 * INFO_GET (a firmware older than INFO; every one of them ran at the built-in rates, fw/limits.h)
 * gets the built-in rates, with a warning that says so; one whose rates tsectl cannot judge at
 * is an error.  Returns EXIT_OK with *r, or an exit status (said). */
int ctl_rates(tlink *l, fw_rates *r);

#endif
