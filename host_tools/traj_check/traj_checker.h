/* A trajectory checked row by row before anything is sent, by the controller's own rules: the
 * firmware's trajectory validator (fw/traj.h) with the limits the controller derives from its
 * parameters (fw/limits.h), from rest at the pose and slides it reports, on the rows as the wire
 * carries them (poses in whole micrometres and microradians, times in whole microseconds).  What
 * passes here can still be refused while streaming (the board computes in float, and the slides
 * it starts from are its exact ones), but only at a margin's width.  No heap, no I/O. */
#ifndef TSE_TRAJ_CHECKER_H
#define TSE_TRAJ_CHECKER_H

#include <stdbool.h>
#include <stdint.h>

#include "fw/limits.h"
#include "fw/params.h"
#include "fw/proto_table.h"
#include "fw/traj.h"

typedef struct {
    fw_traj t; /* large (the queue): keep the checker off small stacks */
    tse_geometry g;
    fw_limits lim; /* as the controller derives them at its rates */
} traj_checker;

/* The geometry and limits a controller at rates r derives from set s (fw_limits_from_params): 0, or
 * -1 when it would refuse the set or cannot run at r (fw_rates_run). */
int traj_limits(const fw_param_set *s, fw_rates r, tse_geometry *g, fw_limits *lim);

/* Starts at rest at pose0 [m, rad] with slides q0 [m] under parameter set s, for a controller
 * running at rates r (its INFO's; FW_RATES_BUILT_IN offline).  Returns 0, or -1 when that controller
 * would refuse the set itself (or cannot run at r). */
int traj_checker_start(traj_checker *c, const fw_param_set *s, fw_rates r, const double pose0[6],
                       const double q0[6]);

/* The next row, dt_us after the previous one (the first: after the start), pose [m, rad] rounded
 * as the wire rounds it; `last` for the trajectory's last row.  Returns 0, or 1 with the REJECT
 * the controller would send for it in reject[] (REJECT's fields in table order, seq 0). */
int traj_checker_push(traj_checker *c, uint32_t dt_us, const double pose[6], bool last,
                      int32_t reject[PROTO_MAX_FIELDS]);

/* The worst slide speed and acceleration so far against their limits (1 = at the limit). */
void traj_checker_peaks(const traj_checker *c, double *v_peak, double *a_peak);

/* The same since the previous call (or the start), then forgotten: called after each row, a row's
 * own (the planner's figure of rows near a limit).  The check of the rows after is unchanged. */
void traj_checker_take_peaks(traj_checker *c, double *v_peak, double *a_peak);

#endif
