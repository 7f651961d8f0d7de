/* What a platform gives the controller (fw/controller.h): its hardware, its configuration, and room
 * for it.  Types only: the controller's own files and its users both build on them. */
#ifndef FW_PLATFORM_H
#define FW_PLATFORM_H

#include <stddef.h>
#include <stdint.h>

#include "hal/can.h"
#include "hal/clock.h"
#include "hal/inputs.h"
#include "hal/stepper.h"
#include "hal/storage.h"
#include "tse/real.h"

/* The hardware, and the context (fw/runtime.h) that calls each part:
 *   can.send, can.receive             the thread
 *   can.state                         the control tick
 *   inputs.limits, inputs.estop       the control tick
 *   stepper.set_dir, stepper.pulse    the step interrupt
 *   stepper.enable                    the control tick; off also from the e-stop paths (any)
 *   stepper.timing                    the control tick (a parameter change at rest), and fw_init
 *   clock.now_us                      the control tick and the thread
 *   storage.load, storage.save        fw_init, the thread */
typedef struct {
    hal_can can;
    hal_stepper stepper;
    hal_inputs inputs;
    hal_clock clock;
    hal_storage storage;
} fw_hal;

typedef struct {
    /* 1..15, or 0: the controller's `node` parameter, as stored (fw_init resolves it, and
     * fw_config_of then reads the id it answers on until the next start). */
    uint8_t node;
    uint32_t segment_hz; /* control segments per second (>= 1000 on the board) */
    uint32_t step_hz;    /* step interrupts per second, a multiple of segment_hz */
    /* The control tick in a context of its own, running at once with the thread (the board's
     * timer interrupt, the simulator's tick thread): the thread hands a command over and calls
     * await(await_ctx) until the tick has taken it (a wait for an interrupt, a yield; never a
     * lock the tick could wait on).  NULL: one context runs everything in turn (tests, rigs,
     * benchmarks), and the tick's side of a hand-over runs in place. */
    void (*await)(void *ctx);
    void *await_ctx;
    /* What the board is, up to 8 ASCII characters (INFO_GET page 1, BOARD): the board image's
     * TSE_BOARD_NAME, "tse-sim" for the simulator.  NULL: an empty name. */
    const char *board;
} fw_config;

typedef struct fw_controller fw_controller;

/* Room for one controller (static storage on the board; anywhere on the host).  The firmware
 * checks at compile time that its controller fits, and that the room is not much larger. */
#if TSE_REAL_FLOAT
#define FW_CONTROLLER_BYTES 7680u
#else
#define FW_CONTROLLER_BYTES 12288u
#endif
typedef union {
    max_align_t align;
    unsigned char bytes[FW_CONTROLLER_BYTES];
} fw_controller_mem;

#endif
