/* The controller as tse-sim runs it, on the fake clock: the firmware; the fault layer (hal/fault)
 * around its bus, its switches and its drives; the real plant (hal/posix) behind them; the fake
 * HAL's bus, clock and parameter storage, in one context: a control period is fw_run_period, the
 * plant taking each step tick.
 *
 * After every period rig_tick checks what must hold whatever the faults, and fails the test
 * otherwise:
 *   - the plant saw no breach (never beyond the mechanical stroke, no step with the drives off,
 *     pulse timing, slide speed and acceleration within the limits) beyond allowed_breaches;
 *   - state and fault are valid values; the drives are as the controller believes, and off in
 *     disabled, fault and e-stop;
 *   - steps only in a period that began or ended homing, moving or stopping;
 *   - an open e-stop input seen by a control tick: state ESTOP and no step in that period (and
 *     none after it until the state changes, by the rule above);
 *   - outside homing (where the zero is set), the controller's count of each slide moves exactly
 *     with the steps the drives were given: the plant's steps plus those the fault layer did not
 *     let it take.  A count that drifted from the pulses would be a lost step of the controller's
 *     own making. */
#ifndef TESTS_SIM_RIG_H
#define TESTS_SIM_RIG_H

#include <stdbool.h>
#include <stdint.h>

#include "fake_hal.h"
#include "fw/controller.h"
#include "fw/inspect.h"
#include "fw/runtime.h"
#include "hal_fault/fault_can.h"
#include "hal_fault/fault_inputs.h"
#include "hal_fault/fault_stepper.h"
#include "hal_posix/plant.h"
#if SIM_RIG_BOARD_TIME
#include "board_time.h"
#endif

#define RIG_CONTROL_HZ 1000u
#define RIG_STEP_HZ 100000u
#define RIG_LOG 4096u

typedef struct {
    uint64_t t_us;   /* when it reached the host */
    hal_can_frame f;
} rig_frame;

typedef struct {
    fake_hal bus;             /* bus, clock, storage; its stepper and inputs are not used */
    fw_controller_mem fw_mem;
    fw_controller *fw;        /* in fw_mem: a copy of the rig holds its own pointer only once copied back */
    tse_plant plant;
    fault_can can;            /* tests configure the faults through can.cfg, inputs.cfg, stepper.cfg */
    fault_inputs inputs;
    fault_stepper stepper;
    hal_inputs in;            /* the inputs as the firmware reads them */
    bool host_alive;          /* rig_run sends a heartbeat every 10 ms (default true) */
    uint8_t seq;              /* the host's next sequence number */
    uint32_t allowed_breaches;/* plant breaches the test expects (a stall stops a slide dead) */
    void (*after_poll)(void *arg); /* called right after each fw_poll (NULL: nothing) */
    void *after_poll_arg;

    rig_frame log[RIG_LOG];   /* ACK, REJECT and STATUS frames the host received, the last RIG_LOG */
    unsigned nlog;            /* received so far (log index nlog % RIG_LOG is the next) */

    uint64_t ticks;           /* control periods run */
    uint32_t state_ms[FW_STATE_COUNT];
    bool offset_known;
    int64_t offset[6];        /* count - (taken + lost) of each slide since the last homing */
    uint64_t lost_at_zero;    /* the fault layer's lost steps when homing last set the zero */
    uint64_t poses_checked;   /* control periods whose true slides the double FK placed (check) */
    uint64_t next_heartbeat;  /* the control period of the host's next heartbeat */
#if SIM_RIG_BOARD_TIME
    /* Built with SIM_RIG_BOARD_TIME (the *_board tests): the board's timing (board_time.h).  The
     * thread's work (a poll, whatever it costs) is charged at 168 MHz and preempted by the control
     * and step ticks where they come due, as on the board; a control period is then a
     * millisecond of board time, and the checks above run at every control tick for the period
     * before it, wherever the tick falls (inside a frame's handling too). */
    board_time bt;
    uint64_t allowed_lost_ticks; /* control ticks the test lets be lost (else the rig fails at one) */
    bool period_open;         /* a control tick has run: its period is checked at the next */
    bool p_estop_open;
    fw_state p_s0;
    uint64_t p_emitted0;
#endif
} sim_rig;

/* A controller with the default parameters, the plant built from them, its slides at start_m;
 * no fault configured (delay_us 20 ms, as tse-sim's default, for a test that delays).  Time is 0. */
void rig_boot(sim_rig *r, double start_m);

/* One control period; then the checks above.  Board timing: the thread's work once, then the
 * board idles to the next period's start (a long work runs past it, its periods elapse inside). */
void rig_tick(sim_rig *r);
/* ms control periods, with a heartbeat every 10 ms while host_alive. */
void rig_run(sim_rig *r, uint32_t ms);
/* Runs until the state is s (true), or max_ms have passed (false). */
bool rig_until(sim_rig *r, fw_state s, uint32_t max_ms);

void rig_send(sim_rig *r, proto_msg m, const int32_t *v);
/* A command whose only field is a sequence number: the next one, returned. */
uint8_t rig_cmd(sim_rig *r, proto_msg m);
void rig_stage(sim_rig *r, uint8_t s, const double pose[6]);
/* POSE_A..C and MOVE_COMMIT (duration ms) under the next sequence number, returned. */
uint8_t rig_move(sim_rig *r, const double pose[6], int32_t ms);

/* Enable, home, and wait for rest: ends IDLE, homed, the counts those of the plant. */
void rig_home(sim_rig *r);

/* What the host received since log index `from` for `function` (and, unless seq < 0, that
 * sequence number): 'a' an ACK, 'r' a REJECT (its reason in *reason), 0 nothing.  The first. */
char rig_answer(const sim_rig *r, unsigned from, uint8_t function, int seq, uint8_t *reason);
/* How many ACKs and REJECTs for `function` the host received since `from`. */
unsigned rig_answers(const sim_rig *r, unsigned from, uint8_t function);
/* The newest STATUS the host received since `from`, decoded (fails if none). */
proto_message rig_status(const sim_rig *r, unsigned from);

/* The controller's observable state now (fw/inspect.h). */
fw_inspection rig_now(const sim_rig *r);

/* The plate's true pose (forward kinematics of the plant's slides) within 10 um and 1e-5 rad of
 * want. */
bool rig_plate_at(sim_rig *r, const double want[6]);
/* The controller's count of slide k against the plant's true position, in steps. */
int64_t rig_count_error(const sim_rig *r, int k);

#endif
