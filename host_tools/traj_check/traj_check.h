/* A whole trajectory file checked before anything is sent (tsectl trajectory, tse-kin check): the
 * shared checker (traj_checker.h, the controller's own validator) over the file's rows. */
#ifndef TSECTL_TRAJ_CHECK_H
#define TSECTL_TRAJ_CHECK_H

#include <stdint.h>

#include "fw/limits.h"
#include "fw/params.h"
#include "fw/proto.h"
#include "traj_file.h"

typedef struct {
    int row;            /* index of the first refused row, or -1 */
    proto_message why;  /* a REJECT as the controller would send it for that row */
    double v_peak, a_peak; /* worst slide speed and acceleration against their limits (1 = at the limit) */
    double v_limit;        /* the slide speed limit in effect [m/s] (fw_limits_from_params) */
    fw_slide_limit v_by;   /* and what sets it */
} traj_check_result;

/* The row's dt on the wire: differences of the rows' times in whole microseconds, so the times add
 * up exactly. */
uint32_t traj_dt_us(const traj_row *rows, int i);

/* Checks rows[0..n) from rest at pose0 with slides q0, under set s at rates r (traj_checker_start).
 * Returns 0 when every row passes, 1 when one is refused (r->row, r->why), -1 when the parameter
 * set itself is refused at those rates. */
int traj_check(const fw_param_set *s, fw_rates rates, const double pose0[6], const double q0[6], const traj_row *rows,
               int n, traj_check_result *r);

#endif
