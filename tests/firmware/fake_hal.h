/* A fake of every hal/ interface with a minimal plant: six slides that integrate the steps they
 * are given (their true position, in steps from s = 0), low homing switches pressed at and below
 * switch_at, an e-stop input, a CAN bus made of two frame queues, and a clock the test advances.
 * A hook lets a test act in the middle of the controller's work (an interrupt arriving while it
 * reads the clock, the bus or the bus state).  For controller tests on the host. */
#ifndef TESTS_FAKE_HAL_H
#define TESTS_FAKE_HAL_H

#include <stdbool.h>
#include <stdint.h>

#include "fw/controller.h"
#include "fw/proto.h"

#define FAKE_QUEUE 4096
/* Where the switches sit by default: 0.2 m at 1.28M steps/m, the default home_sw_k. */
#define FAKE_SWITCH_AT 256000

typedef enum {
    FAKE_AT_CLOCK,     /* a clock read */
    FAKE_AT_RECEIVE,   /* a frame receive */
    FAKE_AT_CAN_STATE, /* a bus state read */
    FAKE_AT_ENABLE     /* the drives being switched on, before the output changes */
} fake_hook_point;

typedef struct {
    hal_can_frame rx[FAKE_QUEUE]; /* to the controller */
    unsigned rx_head, rx_count;
    hal_can_frame tx[FAKE_QUEUE]; /* from the controller */
    unsigned tx_count;
    hal_can_state can_state;

    int32_t steps[6];      /* true position in steps from s = 0 */
    int32_t switch_at[6];  /* a low switch is pressed at or below this many steps */
    uint8_t forward_mask;
    bool enabled;
    bool estop_open;
    uint16_t forced_limits;
    uint64_t pulses;
    uint32_t pulse_ns, dir_setup_ns; /* as last programmed through hal_stepper.timing */
    uint32_t timing_calls;

    /* Called at the points of fake_hook_point (NULL: nothing). */
    void (*hook)(void *arg, fake_hook_point at);
    void *hook_arg;

    uint64_t now_us;

    uint8_t storage[256];
    int storage_len;
    bool storage_fails;
} fake_hal;

void fake_hal_init(fake_hal *f, fw_hal *hal);

/* Queues a frame for the controller. */
void fake_send(fake_hal *f, uint16_t id, uint8_t len, const uint8_t *data);

/* Encodes a message to `node` from its field values in table order; 0, or -1 when a value is out
 * of range (proto_encode). */
int fake_encode(uint8_t node, proto_msg m, const int32_t *values, hal_can_frame *fr);

/* Encodes a message to `node` and queues it for the controller (the values must be in range). */
void fake_send_msg(fake_hal *f, uint8_t node, proto_msg m, const int32_t *values);

/* Runs the controller for ms milliseconds of simulated time, a control period at a time
 * (fw_run_period), the clock advanced after each. */
void fake_run(fake_hal *f, fw_controller *c, uint32_t ms);

/* One control period with only the control tick and its step ticks running, as when the
 * controller's thread is not scheduled (no fw_poll): the clock advanced first. */
void fake_tick_alone(fake_hal *f, fw_controller *c);

/* The newest frame the controller sent with this function code (NULL if none), searching from
 * index `from`. */
const hal_can_frame *fake_last(const fake_hal *f, uint8_t function, unsigned from);

#endif
