/* General-purpose I/O ports of the STM32F405/407 (RM0090 section 8). */
#ifndef TSE_REGS_GPIO_H
#define TSE_REGS_GPIO_H

#include <stddef.h>
#include <stdint.h>

typedef struct {
    volatile uint32_t MODER;   /* 0x00: 2 bits a pin, 00 input, 01 output, 10 alternate, 11 analog */
    volatile uint32_t OTYPER;  /* 0x04 */
    volatile uint32_t OSPEEDR; /* 0x08 */
    volatile uint32_t PUPDR;   /* 0x0C: 01 pull-up, 10 pull-down */
    volatile uint32_t IDR;     /* 0x10 */
    volatile uint32_t ODR;     /* 0x14 */
    volatile uint32_t BSRR;    /* 0x18: low half sets, high half resets, atomically */
    volatile uint32_t LCKR;    /* 0x1C */
    volatile uint32_t AFR[2];  /* 0x20, 0x24: 4 bits a pin */
} tse_gpio_regs;

_Static_assert(offsetof(tse_gpio_regs, BSRR) == 0x18, "GPIO BSRR offset");
_Static_assert(offsetof(tse_gpio_regs, AFR) == 0x20, "GPIO AFR offset");

/* Port 0 = A .. 8 = I, 1 KiB apart (RM0090 table 1). */
#define TSE_GPIO(port) ((tse_gpio_regs *)(0x40020000u + 0x400u * (uint32_t)(port)))

#define GPIO_MODE_INPUT 0u
#define GPIO_MODE_OUTPUT 1u
#define GPIO_MODE_AF 2u
#define GPIO_PULL_UP 1u
#define GPIO_SPEED_HIGH 2u

#endif
