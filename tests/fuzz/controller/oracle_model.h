/* What the controller fuzz target's oracle keeps between calls, and what its two halves share
 * (oracle.c: the lifecycle, the outputs and the promises of every moment; answers.c: the answers
 * to one frame).  Not the target's contract: that is oracle.h. */
#ifndef FUZZ_CONTROLLER_ORACLE_MODEL_H
#define FUZZ_CONTROLLER_ORACLE_MODEL_H

#include <stdbool.h>
#include <stdint.h>

#include "rig.h"
#include "snapshot.h"
#include "wire.h"

/* The model: what the host has been told, as the answers said, and the frame being fed. */
typedef struct oracle_model {
    fw_param_set params, saved; /* in force, and in the flash, as the answers said */
    fw_state state;             /* as last seen */
    bool homed;
    bool estop_cut;             /* the e-stop interrupt fired, ESTOP not yet entered */
    bool cut_inside;            /* ... inside the work that runs now, which may not complete it */
    bool estop_read;            /* the e-stop input as the last control tick read it (STATUS says it) */
    bool estop_read_unsure;     /* an e-stop interrupt came inside that tick: before its read or after */
    bool passive_read;          /* the CAN controller's error-passive state, likewise */
    int32_t steps_read[6];      /* the plant's steps at the last control tick (SLIDES says them) */
    int32_t steps_handed[6];    /* ... or when a command was handed over or a fault reported since:
                                   both publish the view too */
    bool handed;
    /* ... or at any control tick since the outputs were last read: on the board's timing several
     * may run inside one poll, after its telemetry was queued (the newest is steps_read). */
    int32_t steps_ticks[8][6];
    unsigned n_ticks;
    /* The telemetry burst being read: SLIDES [m] and FK [m, rad] as sent, bit k of have for
     * slide k, bit 6 + k for pose coordinate k. */
    double tel_q[6], tel_fk[6];
    unsigned tel_have;
    /* The staged pose as docs/protocol.md's staging rules and the refusals make it. */
    uint8_t stage_seq, stage_have;
    int32_t stage_v[6];
    bool any_commit;
    uint8_t last_commit;
    bool traj_running, traj_stopped;
    uint64_t last_alive_us;     /* the host's last heartbeat, or ENABLE: when it was fed */
    fw_fault seen_fault, seen_pending;
    bool status_seen;
    uint16_t status_counter;
    unsigned queue_capacity;    /* depth + free, as the first answer said */
    /* The frame being fed. */
    wire_frame wf;
    uint64_t fed_us;            /* when (the thread handles it at once; on the board's timing the
                                 * poll may end much later) */
    snapshot before;
    bool estop_open_before, storage_fails_before;
    bool spent_now;             /* it was a commit refused for its content */
    bool cut_pending;           /* an e-stop interrupt waits to be completed as the frame comes */
    /* Slides whose homing saw a low switch the rig forced pressed: a lying switch gives the
     * controller a zero it cannot know is wrong (once homed it catches a lie of more than
     * 0.5 mm, not less), so their positions are not held to the plant's until homed again. */
    uint8_t zero_suspect;
} oracle_model;

/* The answers, parameter values, INFO and BOARD one poll sent (the last of each kind), and where
 * the last ACK, INFO and BOARD stood among the frames it sent. */
typedef struct {
    int n_ack, n_rej, n_pv, n_info, n_board;
    int64_t ack[PROTO_MAX_FIELDS], rej[PROTO_MAX_FIELDS], pv[PROTO_MAX_FIELDS], info[PROTO_MAX_FIELDS];
    int64_t board[PROTO_MAX_FIELDS];
    int ack_at, info_at, board_at;
} oracle_outputs;

/* Judges the answers `out` to the frame o->wf, fed with the controller in o->before, and updates
 * the model from them.  hooked: an e-stop interrupt came inside the frame's poll, or was
 * completed by it before the frame, or (board timing) a control tick ran inside the frame's poll:
 * the state the frame met is then not known for sure. */
void oracle_judge_answers(oracle_model *o, rig *r, const oracle_outputs *out, bool hooked);

#endif
