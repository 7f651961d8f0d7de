/* Long work in pieces.  Validation walks a path piece by piece or segment by segment (a move, a
 * blend, a trajectory row): each calls fw_work_point() once per piece, which every few calls
 * gives the controller's thread a look at the bus (heartbeats taken, a STOP or an e-stop seen,
 * STATUS and telemetry sent when due: fw/runtime.h) and counts its progress for the watchdog.
 * So however long a validation takes, the board is never held from the bus longer than a few
 * pieces' work (`frame_worst` in scripts/target_bench.sh, docs/validation.md).  A walk told to stop returns at once,
 * refused as FW_REASON_STATE (the caller knows why).
 *
 * Outside the controller's thread (host tools, tests of the planner) nothing is watching: the
 * point is a counter and never stops a walk.  One watcher at a time, set and cleared by the
 * thread around its own validation. */
#ifndef FW_WORK_H
#define FW_WORK_H

#include <stdbool.h>

/* Looks every this many points: a piece or a segment is one inverse kinematics solve or more
 * (about 1,200 instructions on the board), so a look comes every 50 us or so of validation. */
#define FW_WORK_STRIDE 8u

/* Returns true when the work is to stop. */
typedef bool (*fw_work_watch)(void *ctx);

void fw_work_begin(fw_work_watch watch, void *ctx);
void fw_work_end(void);

/* One piece done: true when the walk must stop now. */
bool fw_work_point(void);

#endif
