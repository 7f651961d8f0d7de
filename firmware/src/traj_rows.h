/* A streamed trajectory's life as the thread sees it: which rows may join it (its identity, chosen
 * by the host for its first row, and its sequence), and how it ended, which the thread reports once
 * (TRAJ_END) and keeps, so that a row of it still coming is refused `ended`, saying how and how long
 * before. */
#ifndef FW_TRAJ_ROWS_H
#define FW_TRAJ_ROWS_H

#include <stdbool.h>

#include "controller_internal.h"

/* The ends the tick told (publish.h), each sent as TRAJ_END.  Before any row is judged. */
void fw_rows_collect(fw_controller *c);

/* A TRAJ_COMMIT taken: its first row begins the run (with the host's identity). */
void fw_rows_took(fw_controller *c, uint8_t seq, bool first, uint8_t id);

/* Why a TRAJ_COMMIT may not join a trajectory: FW_REASON_NONE, or ORDER or ENDED with the REJECT's
 * field and where in *field, *where.  `ended_only`: only a row of the trajectory that ended last
 * (checked before the state table, so that it is refused `ended` in any state). */
fw_reason fw_rows_refusal(const fw_controller *c, const proto_message *m, bool ended_only, uint8_t *field,
                          int32_t *where);

#endif
