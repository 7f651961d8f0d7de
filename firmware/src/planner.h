/* The thread's planning of a MOVE_COMMIT: the move validated whole (fw/move.h), and, for one
 * committed during another, the blend into it walked as execution will run it; watched by the
 * inbox (a STOP or an e-stop ends it).  The plan goes into the hand-over's request. */
#ifndef FW_PLANNER_H
#define FW_PLANNER_H

#include <stdbool.h>

#include "controller_internal.h"

typedef enum {
    FW_PLAN_OK,      /* the request holds the move */
    FW_PLAN_REFUSED, /* the path is refused: *why says why */
    FW_PLAN_STOPPED  /* a STOP or an ESTOP came while it was validated (inbox.h) */
} fw_plan_outcome;

/* Plans the move to `to`: from rest where the view has the plate (successor false), or from the
 * end of the move last handed over, blended into it where the path allows (successor true). */
fw_plan_outcome fw_plan_commit(fw_controller *c, const tse_real to[6], fw_move_kind kind, tse_real value, bool successor,
                               fw_plan_result *why);

#endif
