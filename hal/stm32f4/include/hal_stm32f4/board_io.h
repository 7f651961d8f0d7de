/* The board's I/O as the firmware's HAL sees it (hal/stepper.h, hal/inputs.h, hal/clock.h,
 * hal/ticker.h), on the pins and timers of pinmap.h. */
#ifndef TSE_BOARD_IO_H
#define TSE_BOARD_IO_H

#include <stdbool.h>
#include <stdint.h>

#include "hal/clock.h"
#include "hal/inputs.h"
#include "hal/stepper.h"
#include "hal/ticker.h"

/* Configures every pin of pinmap.h: outputs low (drivers disabled), inputs with pull-ups, the
 * CAN pins on their alternate function.  Call once, after the peripheral clocks are on. */
void board_pins_init(void);

/* STEP/DIR/ENABLE.  timer_hz: the clock of TIM4, which ends each STEP pulse (a one-shot). */
hal_stepper board_stepper_hal(uint32_t timer_hz);

/* Limit switches (pressed, or a broken wire, reads as pressed) and the e-stop input. */
hal_inputs board_inputs_hal(void);

/* The e-stop input on EXTI8: on a rising edge (the NC chain opened) `on_estop(arg)` runs at
 * PRIO_ESTOP, i.e. without waiting for the main loop. */
void board_estop_irq_init(void (*on_estop)(void *arg), void *arg);

/* Microseconds from TIM5, a free-running 1 MHz counter extended to 64 bits.  now_us is called
 * from the main loop only (the extension is not interrupt-safe), often enough (every control
 * tick) that the 32-bit counter never wraps twice between calls. */
hal_clock board_clock_hal(uint32_t timer_hz);

typedef struct {
    uint32_t timer_hz;          /* TIM2/TIM3 clock */
    void (*idle)(void);         /* after every control call: feeds the watchdog */
    volatile uint32_t due;      /* control ticks raised by TIM3 */
    uint32_t done;              /* control calls made */
    uint32_t late;              /* control ticks skipped because the main loop was busy */
    volatile uint32_t steps;    /* step interrupts taken */
    volatile int stop;
} board_ticker;

/* hal_ticker on TIM2 (step interrupt) and TIM3 (control tick).  start() runs the main loop in
 * the calling thread: the step function runs in TIM2's interrupt, the control function in the
 * main loop once per tick of TIM3, then `idle`.  A tick missed while the loop was busy is
 * counted in `late` and not replayed: the controller's path time is counted in segments, so a
 * replay would only repeat its supervision. */
hal_ticker board_ticker_hal(board_ticker *t);

/* Stops TIM2, TIM3 and TIM4 and their interrupts (used by tests that start a ticker). */
void board_ticker_halt(void);

#endif
