/* A trajectory's rows to a controller (tsectl trajectory, tsectl path): the controller's state,
 * parameters, rates (INFO), pose and slides read first, the rows checked whole from there by its own
 * validator at its rates, then streamed (cmd_traj.c says what a user may rely on). */
#ifndef TSECTL_TRAJ_SEND_H
#define TSECTL_TRAJ_SEND_H

#include <stdbool.h>

#include "fw/limits.h"
#include "fw/params.h"
#include "telemetry.h"
#include "traj_file.h"
#include "tsectl.h"

typedef struct {
    proto_message st; /* the STATUS read */
    int seq;          /* the sequence number to start at */
    fw_param_set set; /* the controller's parameters */
    fw_rates rates;   /* and rates (ctl_rates) */
    telemetry tel;    /* its pose and slides */
    bool have_start;  /* tel holds both (telemetry is on) */
} traj_session;

/* Reads what a trajectory needs.  need_ready: refuse (EXIT_REJECTED, said why) unless idle and
 * homed.  Returns EXIT_OK or the exit status (reported). */
int traj_prepare(tlink *l, bool need_ready, traj_session *s);

/* Checks rows[0..n) from where the controller is and streams them; errors name PATH:LINE of the
 * row.  Returns the exit status. */
int traj_send(tlink *l, const traj_session *s, const char *path, const traj_row *rows, int n);

#endif
