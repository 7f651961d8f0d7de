#include "planner.h"

#include "handover.h"
#include "inbox.h"

fw_plan_outcome fw_plan_commit(fw_controller *c, const tse_real to[6], fw_move_kind kind, tse_real value, bool successor,
                               fw_plan_result *why)
{
    fw_thread *th = &c->th;
    fw_request *r = fw_handover_request(c, PM_MOVE_COMMIT);
    fw_move *mv = &r->u.move.mv;
    r->u.move.successor = successor;
    r->u.move.blend = false;
    r->u.move.k0 = 0;
    /* A move committed during another starts from that one's end. */
    const tse_real *from = successor ? th->last_move.to : th->view.pose;
    const tse_real *q_from = successor ? th->last_move.q_end : th->view.q;
    fw_inbox_watch_begin(c, successor);
    int rc = fw_move_plan(mv, &th->geom, &th->lim, from, to, kind, value, q_from, why);
    if (rc == 0 && successor) {
        /* Blend if the path allows, else back to back.  The setpoints the tick computes meanwhile
         * are behind us: the tick checks the blend's first segment is still ahead when it takes
         * it. */
        uint32_t k0;
        r->u.move.blend = fw_move_blend(&th->last_move, mv, &th->geom, &th->lim, th->view.segments_run + 2u, &k0) == 0;
        r->u.move.k0 = k0;
    }
    if (fw_inbox_watch_end(c))
        return FW_PLAN_STOPPED;
    return rc == 0 ? FW_PLAN_OK : FW_PLAN_REFUSED;
}
