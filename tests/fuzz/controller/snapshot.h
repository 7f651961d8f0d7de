/* What a refused frame must leave as it was (docs/protocol.md: "Nothing of a refused command is
 * applied"): the controller's observable state, taken before a frame is fed and compared after its
 * REJECT.
 *
 * Compared: the state, the latched and pending faults, homed, the drives (as the controller holds
 * them and as the enable output stands), the parameters and the limits derived from them, the
 * driver timing programmed and the flash, the staged pose, the last accepted commit, the motion
 * (source, the running move's target and timing, a blended successor, the stop ramp), the
 * trajectory queue (depth, end time, open or closed while a trajectory runs) and its life (open,
 * clocked, identity, rows, how the last one ended: with an end the tick posted before the frame
 * taken as the frame's poll takes it first), homing's phase, the
 * step generator's timing, queue and positions, the setpoint, the watchdog's last heartbeat.
 * Not compared: the STATUS counter and the times of the next STATUS and telemetry (periodic output:
 * the poll after the frame may legitimately send them), and the bus-off and overrun counts seen
 * (only the control tick reads those, and none runs between the two snapshots).  Scratch that a
 * refusal may overwrite but nothing reads is left out: the successor move's plan while no
 * successor is queued, and the trajectory's bookkeeping while no trajectory runs (an idle
 * controller's next TRAJ_COMMIT starts a new one from the current pose). */
#ifndef FUZZ_CONTROLLER_SNAPSHOT_H
#define FUZZ_CONTROLLER_SNAPSHOT_H

#include <stdbool.h>
#include <stdint.h>

#include "rig.h"

typedef struct {
    /* The controller's, with what is not compared blanked (see the top). */
    fw_inspection in;
    /* The rig's: the enable output, the driver timing programmed, the flash. */
    bool enable_out;
    uint32_t pulse_ns, dir_setup_ns, timing_calls;
    int storage_len;
    uint8_t storage[256];
} snapshot;

void snapshot_take(const rig *r, snapshot *s);

/* Whether the two snapshots agree.  spent: the frame was a commit refused for its content, which
 * docs/protocol.md says spends its number: last_seq, any_commit and the staged parts may then
 * differ (the oracle checks them against its own model).  stepped: step ticks ran in between (on
 * the board's timing, inside the frame's poll), which move the step generator's queue and
 * positions whatever the frame.  Names the first difference. */
bool snapshot_same(const snapshot *a, const snapshot *b, bool spent, bool stepped, const char **what);

#endif
