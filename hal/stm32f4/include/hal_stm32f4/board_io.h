/* The board's I/O as the firmware's HAL sees it (hal/stepper.h, hal/inputs.h, hal/clock.h), and
 * the two timer interrupts that run the controller's step and control contexts (fw/runtime.h), on
 * pins of the board's description (board_desc.h) and the timers of pinmap.h. */
#ifndef TSE_BOARD_IO_H
#define TSE_BOARD_IO_H

#include <stdbool.h>
#include <stdint.h>

#include "hal/clock.h"
#include "hal/inputs.h"
#include "hal/stepper.h"
#include "hal_stm32f4/board_desc.h"

/* Configures every pin of the description: STEP and DIR low, the drivers disabled (at the ENABLE
 * level board_enable_active_high says), the LED off, inputs with pull-ups, the CAN pins on their
 * alternate function.  Call once, after the peripheral clocks are on (and after
 * board_stepper_hal, for an ENABLE level other than the description's). */
void board_pins_init(void);

/* The status LED on or off (nothing where the board has none). */
void board_led_set(bool on);

/* STEP/DIR/ENABLE.  timer_hz: the clock of TIM4, which ends each STEP pulse (a one-shot).
 * enable_active_high: 1 high enables the drivers, 0 low does, < 0 the description's level (the
 * enable_level parameter, docs/board.md); it sets ENABLE inactive at once, and
 * board_outputs_safe (fault.h) and board_pins_init use the same level from then on (before, the
 * description's). */
hal_stepper board_stepper_hal(uint32_t timer_hz, int enable_active_high);

/* The same on the pins of another description (the benchmark's per-slide path). */
hal_stepper board_stepper_hal_for(const board_desc *d, uint32_t timer_hz, int enable_active_high);

/* Whether ENABLE is active high: the description's level until board_stepper_hal sets another. */
bool board_enable_active_high(void);

/* Limit switches (pressed, or a broken wire, reads as pressed) and the e-stop input. */
hal_inputs board_inputs_hal(void);

/* The e-stop input on its EXTI line (the pin's number): on a rising edge (the NC chain opened)
 * `on_estop(arg)` runs at PRIO_ESTOP, i.e. without waiting for the main loop. */
void board_estop_irq_init(void (*on_estop)(void *arg), void *arg);

/* Microseconds from TIM5, a free-running 1 MHz counter extended to 64 bits.  now_us may be called
 * from the main loop and from the control interrupt (the extension is updated with those two
 * masked for a few instructions: BASEPRI, never the step or e-stop interrupt), often enough (every
 * control tick) that the 32-bit counter never wraps twice between calls. */
hal_clock board_clock_hal(uint32_t timer_hz);

typedef struct {
    uint32_t timer_hz;          /* TIM2/TIM3 clock */
    volatile uint32_t controls; /* control interrupts taken */
    volatile uint32_t steps;    /* step interrupts taken */
    /* The longest a control interrupt began behind its timer's period [us]: TIM3 counts
     * microseconds from each period's start, read first thing.  A figure for a debugger (the
     * board-emu test control_tick_delay reads it), never acted on; a debugger may clear it. */
    volatile uint32_t control_delay_max_us;
} board_ticker;

/* The application's work in the two interrupts (called directly, not through a pointer, so that
 * the stack report sees what each can reach): board_step in the step interrupt (TIM2,
 * PRIO_STEP), board_control in the control interrupt (TIM3, PRIO_CONTROL: below the step
 * interrupt, above CAN). */
void board_step(void);
void board_control(void);

/* Starts the two interrupts, board_step step_hz and board_control control_hz times a second, and
 * returns: the caller's main loop is the controller's thread.  A control call that outlasts its
 * period delays the next (TIM3's flag stays set), never stacks.  Returns 0, or -1 for rates the
 * timers cannot keep exactly. */
int board_ticker_start(board_ticker *t, uint32_t control_hz, uint32_t step_hz);

/* Stops TIM2, TIM3 and TIM4 and their interrupts (used by tests that start a ticker). */
void board_ticker_halt(void);

#endif
