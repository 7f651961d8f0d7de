/* A streamed trajectory's life in the control tick: it opens with its first row, its clock starts
 * once the queue holds traj_lead of it (or its last row, or the queue is full), the plate at rest
 * until then; how it ended is told to the thread once (publish.h), which reports it (TRAJ_END) and
 * refuses the rows of it that still come. */
#ifndef FW_TRAJ_LIFE_H
#define FW_TRAJ_LIFE_H

#include <stdbool.h>

#include "controller_internal.h"

/* Its first row taken (already validated from the current pose): a fresh queue from the pose,
 * the identity the host chose. */
void fw_traj_life_open(fw_controller *c, uint8_t id);

/* A row joins the open trajectory: FW_REASON_NONE, or why not (FW_REASON_ENDED when none is
 * open, the queue's refusals). */
fw_reason fw_traj_life_row(fw_controller *c, const fw_traj_point *p);

/* True while the running trajectory's clock waits for the queue to hold enough; starts it once it
 * does. */
bool fw_traj_life_priming(fw_controller *c);

/* Ends the open trajectory (nothing if none is open): how, the fault for FW_TRAJ_END_FAULT. */
void fw_traj_life_end(fw_controller *c, fw_traj_end how, fw_fault f);

/* The ending of the open trajectory, if any, when motion stops or comes to rest with the pending
 * fault (or none): a fault if one is pending, else `otherwise`. */
void fw_traj_life_end_pending(fw_controller *c, fw_traj_end otherwise);

#endif
