/* A description's pin (board_desc.h) as its GPIO port's registers, for the drivers. */
#ifndef TSE_BOARD_PINS_H
#define TSE_BOARD_PINS_H

#include <stdint.h>

#include "hal_stm32f4/board_desc.h"
#include "hal_stm32f4/regs_gpio.h"

static inline tse_gpio_regs *board_pin_port(uint8_t p)
{
    return TSE_GPIO(BOARD_PIN_PORT(p));
}

/* Puts pin p on alternate function af (pins.c). */
void board_pin_alternate(uint8_t p, unsigned af);

#endif
