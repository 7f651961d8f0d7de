/* The board's CAN controller: bxCAN1 behind the firmware's hal_can (hal/can.h).
 *
 * Frames move between the hardware and two rings (can_ring.h) in interrupts: received frames
 * from FIFO 0 into `rx`, queued frames from `tx` into the three transmit mailboxes.  The
 * firmware's send/receive/state only touch the rings and the error register, so they never wait.
 *
 * Promises:
 * - frames leave in the order send() queued them (TXFP: mailboxes go out in request order, and
 *   mailboxes are loaded in ring order);
 * - FIFO 0 receives only standard data frames for this node or node 0 (bxcan_filter.h);
 * - a frame lost on reception (hardware FIFO overrun, or the rx ring full) counts in rx_overruns;
 * - every entry into bus-off counts in bus_off_events, which state() reports: a bus-off that
 *   automatic recovery (ABOM) ended before the firmware looked is still seen, by every reader;
 * - every wait on a hardware flag is bounded (BXCAN_WAIT_LOOPS iterations, each calling `idle`),
 *   so init returns, naming the flag, on a board without a working controller (QEMU reads the
 *   bxCAN as zeros) or without a bus.
 * Registers are reached only through dev->regs, so host tests run the driver on a RAM block.
 *
 * What the driver expects of the board (its clock, pin and vector code, not this driver):
 * - before bxcan_init: the CAN1 clock enabled (RCC APB1ENR bit 25), PB8 (CAN1_RX) and PB9
 *   (CAN1_TX) on alternate function 9, and pclk_hz = the APB1 clock actually running
 *   (board_clocks.apb1_hz: 42 MHz, or 16 MHz when the board fell back to the HSI);
 * - the vectors CAN1_TX (IRQ 19), CAN1_RX0 (IRQ 20) and CAN1_SCE (IRQ 22) calling
 *   bxcan_tx_isr, bxcan_rx0_isr and bxcan_sce_isr with this device, enabled in the NVIC only
 *   after bxcan_init returned (BXCAN_OK, or BXCAN_ERR_LEAVE_INIT; see below); CAN1_RX1 is never
 *   used (FIFO 1 gets no filter);
 * - hal_can's send() called from one context only (the main loop) and receive() from one
 *   context only: each ring has a single producer and a single consumer. */
#ifndef TSE_BXCAN_H
#define TSE_BXCAN_H

#include <stdatomic.h>
#include <stdbool.h>
#include <stdint.h>

#include "hal/can.h"
#include "hal_stm32f4/can_ring.h"
#include "hal_stm32f4/regs_can.h"

/* Polls per flag wait.  An iteration is a register read and the idle call: about 100 ns on the
 * board at 168 MHz, so 100000 give ~10 ms, far beyond the longest legitimate wait (entering
 * initialisation mode waits for the frame on the bus to end: ~1.1 ms for the longest frame at
 * 125 kbit/s). */
#define BXCAN_WAIT_LOOPS 100000u

typedef enum {
    BXCAN_OK = 0,
    BXCAN_ERR_TIMING,      /* no exact bit timing for this clock and rate (bxcan_timing.h) */
    BXCAN_ERR_NODE,        /* node outside 1..15 */
    BXCAN_ERR_ENTER_INIT,  /* INAK never set: no controller answering (no clock, or QEMU) */
    BXCAN_ERR_WAKE,        /* SLAK never cleared: the controller stayed asleep */
    /* INAK never cleared: the controller is configured but has not seen the bus idle (11
     * recessive bits: no transceiver, or CANRX not connected).  It joins the bus by itself as
     * soon as it does, so the board may go on and enable the interrupts. */
    BXCAN_ERR_LEAVE_INIT,
} bxcan_status;

typedef struct {
    tse_can_regs *regs;
    can_ring rx; /* producer: bxcan_rx0_isr; consumer: receive() */
    can_ring tx; /* producer: send(); consumer: bxcan_tx_isr, or send()'s kick (see bxcan.c) */
    _Atomic uint32_t rx_overruns;    /* written by bxcan_rx0_isr only */
    _Atomic uint32_t bus_off_events; /* written by bxcan_sce_isr only */
    bool boff_seen;                  /* bxcan_sce_isr's last view of ESR.BOFF */
} bxcan_dev;

/* Resets *dev, then sets up the controller at `regs`: initialisation mode, bit timing for
 * bitrate at pclk_hz, automatic bus-off recovery, automatic wake-up, transmission in request
 * order, the filter for `node`, the FIFO 0, transmit and error/bus-off interrupts; then leaves
 * initialisation mode.  idle (may be NULL) runs once per poll of every wait: the board may feed
 * its watchdog there; host tests advance their model of the controller. */
bxcan_status bxcan_init(bxcan_dev *dev, tse_can_regs *regs, uint32_t pclk_hz, uint32_t bitrate,
                        uint8_t node, void (*idle)(void));

const char *bxcan_status_str(bxcan_status s);

/* Interrupt entry points (the board's vectors call them). */
void bxcan_rx0_isr(bxcan_dev *dev); /* FIFO 0 -> rx ring */
void bxcan_tx_isr(bxcan_dev *dev);  /* tx ring -> free mailboxes */
void bxcan_sce_isr(bxcan_dev *dev); /* error status: bus-off entries */

/* The firmware's view.  send() returns -1 only when the tx ring is full (try again later); a
 * frame's id is cut to 11 bits and its len to 8 when it goes out. */
hal_can bxcan_hal(bxcan_dev *dev);

#endif
