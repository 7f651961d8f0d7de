/* CAN controller as the firmware sees it: classic frames with 11-bit identifiers, a non-blocking
 * receive, and the error state a controller needs to detect bus-off.  Implemented by hal/posix
 * (SocketCAN) and hal/stm32f4 (bxCAN); tests substitute a fake. */
#ifndef HAL_CAN_H
#define HAL_CAN_H

#include <stdbool.h>
#include <stdint.h>

#define HAL_CAN_MAX_ID 0x7FFu

typedef struct {
    uint16_t id;     /* 11-bit standard identifier */
    uint8_t len;     /* 0..8 */
    uint8_t data[8];
} hal_can_frame;

typedef struct {
    uint8_t tx_errors;    /* transmit error counter */
    uint8_t rx_errors;    /* receive error counter */
    bool error_passive;
    bool bus_off;         /* in bus-off now */
    /* Times the controller has gone bus-off since it started: a bus-off that automatic recovery
     * ended between two looks still shows here, whoever else read the state meanwhile. */
    uint32_t bus_off_events;
    uint32_t rx_overruns; /* frames lost because the receive queue was full */
} hal_can_state;

typedef struct {
    void *ctx;
    /* Queues a frame.  Returns 0, or -1 when every transmit mailbox is busy (try again later). */
    int (*send)(void *ctx, const hal_can_frame *f);
    /* Takes one received frame.  Returns 1 with *f filled, 0 when none is waiting; never blocks. */
    int (*receive)(void *ctx, hal_can_frame *f);
    void (*state)(void *ctx, hal_can_state *st);
} hal_can;

#endif
