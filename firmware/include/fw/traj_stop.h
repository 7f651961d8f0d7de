/* How a trajectory stops: the law its stop ramp follows, shared by the controller (which runs it)
 * and the path planner (which spaces rows so that the queue always holds one).
 *
 * A stop slows the path's clock: the time rate r goes from 1 to 0, and a slide's acceleration is
 * then the path's own, scaled, plus r' times the slide's path speed v.  A trajectory's rows are
 * straight between points, so most of its acceleration is the change of speed at a point, which
 * the clock's rate scales by r (not r^2, as for a smooth path): the two together stay within
 * slide_amax while |r'| v <= amax (1 - m r), m = FW_PATH_MARGIN the share of the limit the rows may
 * use (fw/path.h).  The fastest stop that keeps to it brakes along
 *     r' = -(amax / v) (1 - m r),   so   1 - m r(t) = (1 - m) e^(k t),   k = m amax / v,
 * which ends (r = 0) at T = ln(1 / (1 - m)) / k, after covering path time D = T (1/m - 1/ln(1/(1-m))).
 * With m = 0.95: T = 3.15 v / amax, D = 2.27 v / amax (a cycloidal ramp within the same bound
 * needs 3.7 v / amax of path). */
#ifndef FW_TRAJ_STOP_H
#define FW_TRAJ_STOP_H

#include "fw/path.h"

/* ln(1 / (1 - FW_PATH_MARGIN)): test_traj_stop.c holds the two together. */
#define FW_TRAJ_STOP_LN TSE_R(2.995732273553991)

/* The ramp's length [s] for the fastest slide speed v [m/s] along it, against amax [m/s^2]; at
 * least min_T. */
tse_real fw_traj_stop_time(tse_real v, tse_real amax, tse_real min_T);

/* The path time [s] a ramp of length T covers. */
tse_real fw_traj_stop_reach(tse_real T);

/* The ramp as it runs, one control period dt at a time. */
typedef struct {
    tse_real gap;  /* 1 - m r */
    tse_real grow; /* e^(k dt) */
} fw_traj_stop;

void fw_traj_stop_begin(fw_traj_stop *s, tse_real T, tse_real dt);
/* The rate r for the next period: 0 once the ramp is over. */
tse_real fw_traj_stop_next(fw_traj_stop *s);

#endif
