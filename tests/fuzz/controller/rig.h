/* The controller fuzz target's test rig: one controller (firmware/) on the fake HAL
 * (tests/firmware/fake_hal.h), a clock counted in step interrupts, and the hooks through which the
 * oracle (oracle.h) watches every step pulse, direction change, drive enable, frame and tick.
 *
 * Time runs as fw/runtime.h orders it: at every control-segment boundary a poll (CAN in and out) and a
 * control tick, between two boundaries step_hz / segment_hz step ticks.  A frame the fuzzer sends
 * is fed alone and followed at once by one poll, at whatever step tick the rig stands, so that its
 * answers and effects belong to it.  Simulated time per input is capped (RIG_CAP_*), so that one
 * execution stays in the milliseconds.
 *
 * Built with FUZZ_BOARD_TIME (the float target, as the board runs the controller): on the board's
 * timing instead (tests/board_time).  Every solve the controller makes is charged its cost at
 * 168 MHz; the control and step ticks are interrupts that preempt the thread's work where they
 * come due, a fed frame's poll included; the thread polls once after each control tick (the main
 * loop) and waits for the tick as the board's does.  The oracle then judges a frame inside whose
 * handling a control tick ran as it judges one an e-stop interrupt came into: from what the
 * tick may have changed meanwhile, not from the snapshot before it. */
#ifndef FUZZ_CONTROLLER_RIG_H
#define FUZZ_CONTROLLER_RIG_H

#include <stdbool.h>
#include <stdint.h>

#include "fake_hal.h"
#include "fw/controller.h"
#include "fw/inspect.h"
#include "fw/runtime.h"
#ifndef FUZZ_BOARD_TIME
#define FUZZ_BOARD_TIME 0
#endif
#if FUZZ_BOARD_TIME
#include "board_time.h"
#endif

/* The fixtures the first input byte picks (modulo RIG_FIXTURES). */
/* The board name the rig gives its controller (fw_config.board): what BOARD must carry. */
#define RIG_BOARD_NAME "fuzzrig"

typedef enum {
    /* tests/firmware/harness.c's: default parameters, 1 kHz segments, 100 kHz steps, the slides
     * just above their switches at 0.2 m; homing takes about 4.4 s of the cap. */
    RIG_HARNESS = 0,
    /* A machine for which homing is short and a simulated second cheap: the switches at 0.395 m,
     * just below the home pose's slides (0.403 m), so the move to the home pose is 8 mm; 64000
     * steps/m (coarse: 15.6 um a step) so that 10 kHz of step interrupts give 0.11 m/s; homing at
     * 10 mm/s with 4 m/s^2 braking.  Saved in the fake flash, as a user would have configured it. */
    RIG_FAST,
    /* RIG_FAST as the board runs it: node 15. */
    RIG_FAST_BOARD,
    /* RIG_FAST with the slides starting on (below) their switches: homing leaves them first. */
    RIG_FAST_ON_SWITCH,
    RIG_FIXTURES
} rig_fixture;

/* Simulated time per input, in seconds: enough for homing and a few short moves. */
#define RIG_CAP_S_HARNESS 7u
#define RIG_CAP_S_FAST 4u

/* Where the fake interrupt hook may fire the e-stop interrupt (fake_hook_point), or none. */
#define RIG_HOOK_NONE (-1)

typedef struct rig {
    fake_hal f;
    fw_controller_mem mem;
    fw_controller *c;      /* in mem */
    fw_hal hal;            /* what the controller was given: the fake's, with the stepper and the bus wrapped */
    hal_stepper inner;     /* the fake's own stepper */
    hal_can inner_can;     /* ... and bus */
    fw_config cfg;
    rig_fixture fixture;
    fw_param_set plant_params; /* the set the plant's switches and step size follow */
    uint32_t ticks_per_segment;
    uint32_t us_per_tick;
    uint64_t tick;         /* step ticks since the start */
    uint64_t cap_ticks;
    bool host_alive;       /* the rig sends HOST_HEARTBEAT every 10 ms */
    uint64_t next_heartbeat_tick;
    uint8_t seq;           /* the host's sequence counter */
    int32_t home_um[6];    /* the home pose in wire units (um, urad), around which poses are made */
    /* The e-stop interrupt armed at a fake hook point: fires at the countdown-th call there. */
    int hook_point;
    unsigned hook_countdown;
    bool in_feed;          /* a fed frame's poll runs (the hook then fired inside it) */
    bool hook_fired_in_feed;
    bool ticks_in_feed;    /* a control tick ran inside the fed frame's poll (board timing) */
    bool steps_in_feed;    /* ... a step tick */
#if FUZZ_BOARD_TIME
    board_time bt;
    uint64_t thread_segment; /* the segment (from 1) of the thread's last turn after its control tick */
#endif
} rig;

/* A fresh rig (fake HAL, fixture, controller through fw_init) and a fresh oracle. */
void rig_start(rig *r, rig_fixture fixture);

/* Whether the input's time is used up. */
bool rig_over(const rig *r);

/* Runs n step ticks, with the polls and control ticks that fall among them. */
void rig_advance(rig *r, uint64_t n);

/* Runs whole milliseconds. */
void rig_run_ms(rig *r, uint32_t ms);

/* Runs until the controller is at rest (neither homing, moving nor stopping) or max_ms passed. */
void rig_run_until_rest(rig *r, uint32_t max_ms);

/* Feeds one frame and polls once, without advancing time; the oracle judges the answers. */
void rig_feed(rig *r, const hal_can_frame *fr);

/* Encodes a message to `node` and feeds it (nothing if a value does not encode). */
void rig_feed_msg(rig *r, uint8_t node, proto_msg m, const int32_t *values);

/* The e-stop input opens (and its interrupt fires at once if isr), or closes. */
void rig_estop_input(rig *r, bool open, bool isr);

/* Arms the e-stop interrupt to fire inside the controller's work, at the n-th (1..) call of the
 * fake's hook point `at` from now. */
void rig_arm_estop_hook(rig *r, fake_hook_point at, unsigned n);

/* A power cycle: the controller starts again from what the fake flash holds; the plant stays. */
void rig_reboot(rig *r);

/* A fault the platform reports (the simulator's plant, the board's hardware). */
void rig_report_fault(rig *r, fw_fault f);

/* An input the controller reads changed (switches, bus state, flash): nothing to check but that
 * nothing answered. */
void rig_input_changed(rig *r);

/* The parameters in force describe the machine: the plant's switches trip where home_sw_k says
 * (pressed at and below it, so at the last whole step at or below), and a new steps_per_m is a
 * new step size of the same slides, whose positions in metres stay.  The oracle calls this on
 * every change of the set. */
void rig_plant_follow(rig *r, const fw_param_set *params);

#endif
