/* The boot line on the description's USART (hal_stm32f4/bootline.h). */
#include "hal_stm32f4/bootline.h"

#include "hal_stm32f4/board_pins.h"
#include "hal_stm32f4/regs_rcc.h"
#include "hal_stm32f4/regs_usart.h"

static tse_usart_regs *usart = TSE_USART1;

static void put(char c)
{
    for (uint32_t i = 0; i < BOOTLINE_WAIT_POLLS; ++i)
        if (usart->SR & USART_SR_TXE) {
            usart->DR = (uint8_t)c;
            return;
        }
}

void board_bootline_open(uint32_t pclk1_hz, uint32_t pclk2_hz)
{
    const board_desc *d = &tse_board_desc;
    uint32_t pclk = pclk2_hz;
    switch (d->boot_usart) {
    case 2:
        usart = TSE_USART2;
        TSE_RCC->APB1ENR |= RCC_APB1ENR_USART2;
        pclk = pclk1_hz;
        break;
    case 3:
        usart = TSE_USART3;
        TSE_RCC->APB1ENR |= RCC_APB1ENR_USART3;
        pclk = pclk1_hz;
        break;
    case 6:
        usart = TSE_USART6;
        TSE_RCC->APB2ENR |= RCC_APB2ENR_USART6;
        break;
    default:
        usart = TSE_USART1;
        TSE_RCC->APB2ENR |= RCC_APB2ENR_USART1;
        break;
    }
    TSE_RCC->AHB1ENR |= 1u << BOARD_PIN_PORT(d->boot_tx);
    (void)TSE_RCC->APB2ENR; /* the enable takes two bus cycles to reach the peripherals */
    board_pin_alternate(d->boot_tx, d->boot_tx_af);
    /* 16x oversampling: BRR holds pclk / baud in sixteenths, rounded to the nearest. */
    usart->BRR = (pclk + BOOTLINE_BAUD / 2u) / BOOTLINE_BAUD;
    usart->CR1 = USART_CR1_UE | USART_CR1_TE;
}

void board_bootline_puts(const char *s)
{
    while (*s)
        put(*s++);
}

void board_bootline_hex(uint32_t v)
{
    board_bootline_puts("0x");
    int shift = 28;
    while (shift > 4 && ((v >> shift) & 0xFu) == 0)
        shift -= 4;
    for (; shift >= 0; shift -= 4)
        put("0123456789abcdef"[(v >> shift) & 0xFu]);
}

void board_bootline_dec(uint32_t v)
{
    char digits[10];
    int n = 0;
    do {
        digits[n++] = (char)('0' + v % 10u);
        v /= 10u;
    } while (v);
    while (n)
        put(digits[--n]);
}
