/* The controller board's timers and interrupt priorities.  The pins are the board description's
 * (board_desc.h, one file a board in hal/stm32f4/boards/; docs/boards.md lists them).
 *
 * Timers (APB1 at 42 MHz, so its timers count at 84 MHz; QEMU's count at 1 GHz whatever the
 * clock tree says):
 * | timer | job                                                                             |
 * |-------|---------------------------------------------------------------------------------|
 * | TIM2  | the step interrupt at step_hz (update event), highest priority; in the benchmark |
 * |       | image, the instruction counter instead                                          |
 * | TIM4  | the end of the STEP pulses: a one-shot of step_pulse_ns started by each pulse,   |
 * |       | whose update interrupt drives the STEP pins low again                           |
 * | TIM3  | the control tick at segment_hz: its interrupt only counts; the main loop runs   |
 * |       | the tick, so all of the controller's state changes in one context               |
 * | TIM5  | free-running 1 MHz counter: the microsecond clock (32 bits, extended to 64)     |
 */
#ifndef TSE_BOARD_PINMAP_H
#define TSE_BOARD_PINMAP_H

/* Interrupt priorities (0 = most urgent).  The step timer and the e-stop share the top level so
 * that neither preempts the other (the e-stop halts the step generator the step interrupt
 * reads); TIM4 ends the STEP pulse (stepout.c: 1); the control tick comes next, so that nothing
 * but stepping delays a setpoint; CAN moves frames between hardware and rings below it (its rings
 * hold what arrives meanwhile).  Frames, planning and validation run in the main loop. */
#define PRIO_STEP 0u
#define PRIO_ESTOP 0u
#define PRIO_CONTROL 2u
#define PRIO_CAN 3u

#endif
