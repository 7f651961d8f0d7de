/* The controller: the state machine of docs/controller.md, the CAN command handling, and the
 * execution of motion at the control segment rate.  Hardware-free: everything physical goes
 * through fw_hal.
 *
 * The platform drives it from three places, and may add a fourth:
 * - fw_step_tick from the step interrupt (step_hz),
 * - fw_control_tick from the control tick (segment_hz): inputs, watchdog, the next segment,
 * - fw_poll from the main loop: CAN frames in and out, periodic status and telemetry,
 * - fw_estop_isr from the e-stop input's interrupt.
 * fw_control_tick and fw_poll must not preempt each other (one context, or one interrupt level);
 * fw_step_tick and fw_estop_isr may preempt them at any point.  In the simulator they are
 * timer-driven calls.
 *
 * The homing switches (bit i of hal_inputs.limits) are references, not ends of travel: slide i's
 * is pressed at and below home_sw_i and released above it, and the slides go below it in
 * legitimate poses.  Homing sets each slide's coordinate at its switch's release edge.  Once
 * homed, a switch that disagrees with the step count by more than FW_HOME_SW_TOLERANCE_UM (lost
 * steps, or a broken switch) is FW_FAULT_LIMIT; before homing they are not checked.  The optional
 * high-end switches (bit 8 + i) are hard limits: pressed outside homing is FW_FAULT_LIMIT. */
#ifndef FW_CONTROLLER_H
#define FW_CONTROLLER_H

#include <stdatomic.h>
#include <stdbool.h>
#include <stdint.h>

#include "fw/move.h"
#include "fw/params.h"
#include "fw/proto.h"
#include "fw/stepgen.h"
#include "fw/traj.h"
#include "fw/types.h"
#include "hal/can.h"
#include "hal/clock.h"
#include "hal/inputs.h"
#include "hal/stepper.h"
#include "hal/storage.h"

typedef struct {
    hal_can can;
    hal_stepper stepper;
    hal_inputs inputs;
    hal_clock clock;
    hal_storage storage;
} fw_hal;

typedef struct {
    uint8_t node;        /* 1..15 */
    uint32_t segment_hz; /* control segments per second (>= 1000 on the board) */
    uint32_t step_hz;    /* step interrupts per second, a multiple of segment_hz */
    /* Refuse (FW_REASON_STATE) a move committed while another runs instead of blending it.  For
     * a platform whose main loop both handles commands and runs the control tick (the board):
     * validating the blend there takes tens of milliseconds, during which the running move's
     * setpoints would stop coming and its slides would halt at speed. */
    bool no_blend;
} fw_config;

/* What a command may do in a state: accept, or refuse with a reason.  One row per command
 * message, one column per state; see controller.c for the table and docs/protocol.md for it
 * printed. */
fw_reason fw_command_allowed(proto_msg cmd, fw_state state);

typedef enum { FW_SRC_NONE, FW_SRC_MOVE, FW_SRC_TRAJ, FW_SRC_JOINT } fw_source;

/* Homing: first every slide finds its switch on its own (HOME_SWITCHES), then all six go to the
 * home pose together (HOME_TO_POSE). */
typedef enum { HOME_SWITCHES, HOME_TO_POSE } fw_home_phase;

/* One slide while finding its switch (homing.c). */
typedef enum {
    HOME_AXIS_LEAVE,   /* started on the switch: up at the homing speed, past the release */
    HOME_AXIS_SEEK,    /* down at the homing speed to the press, then braking */
    HOME_AXIS_RELEASE, /* up at the creep speed to the release edge */
    HOME_AXIS_DONE     /* edge latched */
} fw_home_axis;

typedef struct {
    bool active;        /* homing runs, or is being stopped */
    bool abort;         /* a stop or a fault asked it to come to rest */
    fw_home_phase phase;
    uint8_t axis[6];    /* fw_home_axis of each slide */
    uint8_t released;   /* leaving slides whose switch has released */
    uint8_t hit;        /* seeking slides whose switch has been pressed */
    tse_real v[6];      /* joint speeds [m/s], signed */
    tse_real s[6];      /* joint travel since homing began [m] */
    tse_real mark[6];   /* travel where the slide's phase began (leaving: where it released) */
    int32_t start_steps[6];
    int32_t edge_steps[6]; /* steps emitted when the release edge was seen */
} fw_homing;

/* A streamed trajectory's life (traj_run.c).  Its rows join it by its identity (chosen by the host
 * for its first row) and in sequence; its clock starts once the queue holds traj_lead of it (or
 * its last row, or the queue is full), the plate at rest until then; how it ended is reported once
 * (TRAJ_END) and kept, so that a row of it still coming is refused `ended`, saying how and how
 * long before. */
typedef struct {
    bool open;            /* from its first row until it ends */
    bool clock;           /* its clock runs (kept as it was once it ends) */
    bool report;          /* TRAJ_END still to send (fw_poll sends it) */
    uint8_t id;           /* the open trajectory's identity */
    uint8_t next_seq;     /* the sequence number its next row must carry */
    uint32_t rows;        /* rows it took */
    /* The trajectory that ended last: */
    fw_traj_end ended;    /* how (FW_TRAJ_END_NONE: none has ended) */
    fw_fault fault;       /* the fault that ended it */
    uint8_t ended_id;
    uint32_t ended_rows;
    uint64_t ended_us;    /* when */
} fw_traj_run;

/* A joint-space move (after homing, the robot is not yet at a pose the planner can start from). */
typedef struct {
    tse_real from[6], to[6];
    fw_profile prof; /* of u in [0, 1] */
} fw_joint_move;

typedef struct {
    fw_hal hal;
    fw_config cfg;
    fw_state state;
    fw_fault fault;         /* latched fault (FW_FAULT_NONE when none) */
    fw_fault pending_fault; /* fault to latch once the controlled stop ends */
    bool homed;
    bool drives_on;
    atomic_bool estop_request; /* fw_estop_isr ran; fw_estop still to complete it */

    fw_param_set params;
    tse_geometry geom;
    fw_limits lim;
    stepgen sg;

    tse_real pose[6];       /* pose of the latest segment setpoint */
    tse_real q[6];          /* its slides [m] */
    tse_real q_prev[6];     /* the setpoint before (for the current slide speeds) */
    bool pose_known;

    /* Staged pose */
    uint8_t stage_seq;
    uint8_t stage_have;     /* bit 0: A, 1: B, 2: C */
    int32_t stage_v[6];
    uint8_t last_seq;       /* last accepted commit */
    bool any_commit;

    /* Motion */
    fw_source src;
    fw_move move;
    fw_move next;           /* a move committed while `move` runs, blended into it */
    bool has_next;
    uint32_t blend_k0;      /* segment of `move` at which `next` starts */
    fw_joint_move joint;
    fw_traj traj;
    fw_traj_run run;
    tse_real tau;           /* path time of the running source [s] */
    bool stopping;
    tse_real stop_t, stop_T;/* time into the stop ramp, its length */
    fw_homing home;

    /* Time */
    uint64_t last_heartbeat_us;
    uint64_t next_status_us, next_telemetry_us;
    uint16_t counter;
    uint32_t bus_off_seen;  /* the CAN controller's bus-off count at the last supervision */
    uint32_t overruns_seen; /* the step generator's overrun count at the last supervision */
    uint32_t segments_run;
} fw_controller;

/* Loads the parameters from storage (defaults if none or corrupt) and enters DISABLED.
 * Returns 0, or -1 for a configuration that cannot run. */
int fw_init(fw_controller *c, const fw_hal *hal, const fw_config *cfg);

void fw_poll(fw_controller *c);
void fw_control_tick(fw_controller *c);

/* The step interrupt: one tick of the step generator onto the outputs. */
static inline void fw_step_tick(fw_controller *c)
{
    const stepgen_output o = stepgen_tick(&c->sg);
    if (o.dir_changed)
        c->hal.stepper.set_dir(c->hal.stepper.ctx, o.forward_mask);
    if (o.step_mask)
        c->hal.stepper.pulse(c->hal.stepper.ctx, o.step_mask);
}

/* Handles one received frame (fw_poll calls it for every frame it reads). */
void fw_handle_frame(fw_controller *c, const hal_can_frame *f);

/* The emergency stop: aborts stepping and every queued setpoint, drives off, state ESTOP (latched
 * until CLEAR_FAULT), the zero dropped.  From the main loop's context (the ESTOP command and the
 * polled input call it). */
void fw_estop(fw_controller *c);

/* The emergency stop from an interrupt (the e-stop input's EXTI), of any priority above the main
 * loop's.  At once: the step generator halts (no step from its next tick on; a step tick this
 * interrupt preempted completes) and the drives are switched off through hal_stepper.enable; then
 * it leaves a request that fw_poll, fw_control_tick and fw_handle_frame complete first thing (with
 * fw_estop).  Between the two nothing emits a step: setpoints the interrupted code still pushes
 * only wait in the halted queue, and fw_estop discards them; an ENABLE taken meanwhile does not
 * switch the drives back on. */
void fw_estop_isr(fw_controller *c);

/* A fault the platform detected (the simulator's plant reports FW_FAULT_PLANT, the board
 * FW_FAULT_HARDWARE): a controlled stop if anything moves, then latched, exactly as the
 * controller's own faults. */
void fw_report_fault(fw_controller *c, fw_fault f);

#endif
