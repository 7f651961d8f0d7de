/* The controller board's pins and timers: the one place that says what is wired where.
 * LQFP64 pins only (STM32F405RG), so the same map fits the F405 and the F407.
 *
 * | signal          | pin        | notes                                                        |
 * |-----------------|------------|--------------------------------------------------------------|
 * | STEP1..STEP6    | PC0..PC5   | push-pull outputs, one port: a mask of axes is one BSRR write |
 * | DIR1..DIR6      | PC6..PC11  | push-pull outputs, high = slide moves towards +s             |
 * | ENABLE (shared) | PC12       | push-pull, high = drivers enabled (see ENABLE_ACTIVE_HIGH)  |
 * | LIM1..LIM6      | PA0..PA5   | low-end homing switches, inputs with pull-up; NC switch to   |
 * |                 |            | GND: closed reads 0, pressed (or a broken wire) reads 1      |
 * | LIMH1..LIMH6    | PB0, PB1,  | optional high-end switches, same wiring; only those fitted   |
 * |                 | PB12..PB15 | count (BOARD_HIGH_SWITCHES): an open input reads as pressed  |
 * | E-STOP          | PA8        | NC chain to GND with pull-up: open circuit (1) = e-stop;     |
 * |                 |            | EXTI8 on the rising edge, interrupt EXTI9_5                  |
 * | CAN1_RX/TX      | PB8 / PB9  | alternate function 9, to the transceiver (e.g. TJA1051/SN65HVD230) |
 * | STATUS LED      | PA10       | push-pull, high = on (the Netduino Plus 2's user LED)        |
 * | BOOT LINE TX    | PA9        | USART1 TX (AF7), 115200 8N1: one line at start-up (bootline.h) |
 * | SWDIO/SWCLK     | PA13/PA14  | programming and debug (ST-Link)                              |
 * | OSC_IN/OSC_OUT  | PH0/PH1    | 8 MHz crystal (HSE)                                          |
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

#include "hal_stm32f4/regs_gpio.h"

#define PIN_STEP_PORT TSE_GPIOC
#define PIN_STEP_SHIFT 0u
#define PIN_DIR_PORT TSE_GPIOC
#define PIN_DIR_SHIFT 6u
#define PIN_ENABLE_PORT TSE_GPIOC
#define PIN_ENABLE 12u
#define ENABLE_ACTIVE_HIGH 1

#define PIN_LIM_PORT TSE_GPIOA
#define PIN_LIM_SHIFT 0u
#define PIN_LIMH_PORT TSE_GPIOB
/* High-end switches on PB0, PB1, PB12..PB15, read only where BOARD_HIGH_SWITCHES has the axis's
 * bit (default none: the prototype has none, and an input without a switch reads as pressed). */
#define BOARD_HIGH_SWITCHES 0x00u
static const unsigned char pin_limh[6] = {0, 1, 12, 13, 14, 15};

#define PIN_ESTOP_PORT TSE_GPIOA
#define PIN_ESTOP 8u
#define PIN_ESTOP_EXTI_PORT 0u /* SYSCFG EXTICR code of port A */

#define PIN_CAN_PORT TSE_GPIOB
#define PIN_CAN_RX 8u
#define PIN_CAN_TX 9u
#define PIN_CAN_AF 9u

#define PIN_LED_PORT TSE_GPIOA
#define PIN_LED 10u

#define PIN_BOOT_TX_PORT TSE_GPIOA
#define PIN_BOOT_TX 9u
#define PIN_BOOT_TX_AF 7u

#define STEP_MASK_ALL 0x3Fu

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
