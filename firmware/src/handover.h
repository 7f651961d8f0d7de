/* The hand-over from the thread to the control tick: one command at a time, without a lock.
 *
 * The thread fills the request (fw_handover_request), then fw_handover posts it (a counter, stored
 * with release) and waits until the tick has taken it (fw_config.await; with one context the tick's
 * side runs in place).  The tick, first thing in its next call, completes a pending e-stop, judges
 * the command again by the state table against its own state (which may have changed since the
 * thread judged it against the view: a fault, the end of a motion), applies it, writes the verdict,
 * publishes its state and stores the counter back (release).  The thread reads the verdict and the
 * view after that (acquire) and answers the host.  Only one side writes each part: the thread the
 * request and `posted`, the tick the verdict and `taken`; the tick never waits.
 *
 * What a command hands over and what the tick does with it:
 *   ENABLE, DISABLE, CLEAR_FAULT, HOME, STOP, ESTOP   nothing more (the e-stop halted already);
 *   MOVE_COMMIT   the planned move: started from rest, or joined to the running one (blended if the
 *                 tick has not passed the blend's first segment, else after it), or from rest at the
 *                 running one's end if that ended exactly there meanwhile, or refused `state`;
 *   TRAJ_COMMIT   the validated point: a first row opens a trajectory at rest, the others join the
 *                 open one (refused `ended` if it ended meanwhile, `queue_full`);
 *   PARAM_SET     the prepared set, adopted at rest (else the rule not_at_rest). */
#ifndef FW_HANDOVER_H
#define FW_HANDOVER_H

#include "controller_internal.h"

/* The request to fill, for command msg.  From the thread. */
fw_request *fw_handover_request(fw_controller *c, proto_msg msg);

/* Posts the request filled and waits for the tick's verdict; the view (c->th.view) is then the
 * tick's state after it.  From the thread. */
fw_verdict fw_handover(fw_controller *c);

/* Takes a posted request, if any.  From the tick (first thing), or in place. */
void fw_handover_take(fw_controller *c);

#endif
