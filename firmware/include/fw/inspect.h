/* The controller's observable state in one copy, for tests, the fuzzer's oracle and tools that
 * look inside (tse-sim's log): what it holds, not how.  From the control tick's context or where
 * nothing runs at once (the thread's part, the staging and commits, may be mid-change otherwise). */
#ifndef FW_INSPECT_H
#define FW_INSPECT_H

#include <stdbool.h>
#include <stdint.h>

#include "fw/limits.h"
#include "fw/phases.h"
#include "fw/platform.h"
#include "fw/move.h"
#include "fw/params.h"
#include "fw/stepgen.h"
#include "fw/types.h"

typedef struct {
    /* The state machine (the control tick's) */
    fw_state state;
    fw_fault fault, pending_fault; /* latched; to latch once the controlled stop ends */
    bool homed, drives_on, pose_known;
    tse_real pose[6], q[6]; /* the latest setpoint's pose and slides [m, rad] */
    fw_param_set params;    /* in force */
    fw_limits lim;

    /* Motion */
    fw_source src;
    bool has_next;          /* a move queued behind (or blended into) the running one */
    bool stopping;          /* on a stop ramp */
    tse_real tau;           /* path time of the running source [s] */
    tse_real stop_t, stop_T;/* time into the stop ramp, its length */
    uint32_t segments_run;  /* setpoints of the running source */
    uint32_t blend_k0;      /* segment of `move` at which `next` starts */
    fw_move move, next;     /* the running move, and the one behind it */
    tse_real joint_T, joint_Ta; /* homing's joint move: its length and ramps [s] */

    /* Homing */
    bool home_active, home_abort;
    fw_home_phase home_phase;
    uint8_t home_axis[6];   /* fw_home_axis of each slide */

    /* The trajectory queue (the control tick's) */
    unsigned traj_depth, traj_free;
    uint64_t traj_end_us;   /* path time of its newest point */
    bool traj_closed;       /* its last point is in */
    tse_real traj_tail[6];  /* the newest point the validator took (the thread's) */

    /* The trajectory's life: the one running, and how the last one ended */
    bool run_open, run_clock;
    uint8_t run_id, run_next_seq;
    uint32_t run_rows;
    fw_traj_end run_ended;
    fw_fault run_fault;
    uint8_t run_ended_id;
    uint32_t run_ended_rows;
    uint64_t run_ended_us;
    /* Ends the tick has posted that the thread has not yet taken (its next poll takes them first,
     * before any frame), and the newest of them. */
    uint64_t posted_us;
    uint32_t posted_rows;
    unsigned posted_ends;
    fw_traj_end posted_how;
    fw_fault posted_fault;
    uint8_t posted_id;

    /* Staged pose and commits (the thread's) */
    uint8_t stage_seq, stage_have;
    int32_t stage_v[6];
    uint8_t last_seq;
    bool any_commit;
    uint32_t heartbeat_us;  /* the last heartbeat (ENABLE counts as one), low 32 bits of the clock */

    /* The step generator */
    stepgen_config sg_cfg;
    unsigned sg_queued;
    bool sg_idle, sg_running;
    int32_t sg_pos[6];
    uint32_t sg_overruns;
} fw_inspection;

void fw_inspect(const fw_controller *c, fw_inspection *out);

#endif
