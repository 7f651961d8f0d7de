/* A fake of every hal/ interface with a minimal plant: six slides that integrate the steps they
 * are given, low limit switches at a hidden physical zero, an e-stop input, a CAN bus made of two
 * frame queues, and a clock the test advances.  For controller tests on the host. */
#ifndef TESTS_FAKE_HAL_H
#define TESTS_FAKE_HAL_H

#include <stdbool.h>
#include <stdint.h>

#include "fw/controller.h"

#define FAKE_QUEUE 4096

typedef struct {
    hal_can_frame rx[FAKE_QUEUE]; /* to the controller */
    unsigned rx_head, rx_count;
    hal_can_frame tx[FAKE_QUEUE]; /* from the controller */
    unsigned tx_count;
    hal_can_state can_state;

    int32_t steps[6];      /* physical position in steps from the hidden zero */
    int32_t switch_at;     /* a low switch is pressed at or below this many steps */
    uint8_t forward_mask;
    bool enabled;
    bool estop_open;
    uint16_t forced_limits;
    uint64_t pulses;

    uint64_t now_us;

    uint8_t storage[256];
    int storage_len;
    bool storage_fails;
} fake_hal;

void fake_hal_init(fake_hal *f, fw_hal *hal);

/* Queues a frame for the controller. */
void fake_send(fake_hal *f, uint16_t id, uint8_t len, const uint8_t *data);

/* Encodes a message to `node` and queues it for the controller (the values must be in range). */
void fake_send_msg(fake_hal *f, uint8_t node, proto_msg m, const int32_t *values);

/* Runs the controller for ms milliseconds of simulated time: every step tick, every control tick
 * and a poll per control tick. */
void fake_run(fake_hal *f, fw_controller *c, uint32_t ms);

/* The newest frame the controller sent with this function code (NULL if none), searching from
 * index `from`. */
const hal_can_frame *fake_last(const fake_hal *f, uint8_t function, unsigned from);

#endif
