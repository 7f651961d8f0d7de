/* The clock tree: 168 MHz SYSCLK from the board's crystal (board_desc.h) through the PLL, AHB 168 MHz, APB1
 * 42 MHz (timers 84 MHz), APB2 84 MHz, flash at 5 wait states with the ART accelerator
 * (prefetch, instruction and data caches), regulator scale 1.
 *
 * Every wait on a hardware flag is bounded.  When one times out (a dead crystal; or QEMU, which
 * models no RCC), the board stays on the 16 MHz internal oscillator, says which wait failed, and
 * the application raises a hardware fault: the controller then refuses to move, but it boots,
 * talks and can be inspected.  So does a crystal that runs but measures more than 2 % off the
 * frequency the PLL is set for (hse_check.h), before the PLL is started. */
#ifndef TSE_BOARD_CLOCK_H
#define TSE_BOARD_CLOCK_H

#include <stdint.h>

#include "hal_stm32f4/hse_check.h"

typedef struct {
    uint32_t sysclk_hz;
    uint32_t apb1_hz;       /* the CAN controller's clock */
    uint32_t apb1_timer_hz; /* TIM2..TIM5 */
    uint32_t apb2_hz;       /* USART1 (the boot line) */
    const char *failed;     /* NULL, or the flag that never came ("HSERDY", "PLLRDY", "SWS"), or
                               "crystal": measured off its frequency (crystal says how) */
    hse_check crystal;      /* the crystal measured against the HSI before the PLL (hse_check.h) */
} board_clocks;

/* Sets up the tree above, or leaves the reset clocks (HSI 16 MHz, no prescalers) on a timeout
 * or a crystal off its frequency. */
board_clocks board_clock_init(void);

/* Enables the peripheral clocks the board uses (GPIOA..C, TIM2..5, CAN1, SYSCFG, PWR). */
void board_clock_enable_peripherals(void);

#endif
