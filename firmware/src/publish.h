/* What the control tick tells the thread: its state as a view (fw_view), and how trajectories
 * ended.  Lock-free: the tick never waits for the thread.
 *
 * The view is a sequence lock: the tick makes the counter odd, writes the words, makes it even; the
 * thread copies the words between two reads of an even counter and tries again if it changed (the
 * tick wrote meanwhile: it preempted the copy, or on the host ran at once).  The words are atomics
 * (relaxed) so that a copy racing a write is not undefined, only discarded. */
#ifndef FW_PUBLISH_H
#define FW_PUBLISH_H

#include <stdbool.h>

#include "controller_internal.h"

/* The tick's state into the view.  From the tick's context (or fw_init, or a hand-over taken in
 * place): every call of the tick ends with it. */
void fw_publish(fw_controller *c);

/* The view as the tick last published it, into c->th.view.  From the thread. */
void fw_view_read(fw_controller *c);

/* The same into a copy of the caller's. */
void fw_view_read_into(fw_controller *c, fw_view *out);

/* A trajectory ended: for the thread's TRAJ_END.  From the tick.  Returns false, dropping it, if
 * the thread has not taken the ends before it (a ring of FW_ENDED_RING: a trajectory starts only
 * through the thread, which takes the ends first, so this does not happen). */
bool fw_ended_post(fw_controller *c, const fw_traj_ended *e);

/* The oldest end not yet taken.  From the thread.  Returns false when there is none. */
bool fw_ended_take(fw_controller *c, fw_traj_ended *e);

#endif
