/* The boot line on USART1 (hal_stm32f4/bootline.h). */
#include "hal_stm32f4/bootline.h"

#include "hal_stm32f4/pinmap.h"
#include "hal_stm32f4/regs_rcc.h"
#include "hal_stm32f4/regs_usart.h"

static void put(char c)
{
    for (uint32_t i = 0; i < BOOTLINE_WAIT_POLLS; ++i)
        if (TSE_USART1->SR & USART_SR_TXE) {
            TSE_USART1->DR = (uint8_t)c;
            return;
        }
}

void board_bootline_open(uint32_t pclk2_hz)
{
    TSE_RCC->AHB1ENR |= RCC_AHB1ENR_GPIOA;
    TSE_RCC->APB2ENR |= RCC_APB2ENR_USART1;
    (void)TSE_RCC->APB2ENR; /* the enable takes two bus cycles to reach the peripherals */
    const unsigned pin = PIN_BOOT_TX;
    PIN_BOOT_TX_PORT->AFR[pin >> 3] = (PIN_BOOT_TX_PORT->AFR[pin >> 3] & ~(0xFu << (4u * (pin & 7u)))) |
                                      PIN_BOOT_TX_AF << (4u * (pin & 7u));
    PIN_BOOT_TX_PORT->MODER = (PIN_BOOT_TX_PORT->MODER & ~(3u << (2u * pin))) | GPIO_MODE_AF << (2u * pin);
    /* 16x oversampling: BRR holds pclk / baud in sixteenths, rounded to the nearest. */
    TSE_USART1->BRR = (pclk2_hz + BOOTLINE_BAUD / 2u) / BOOTLINE_BAUD;
    TSE_USART1->CR1 = USART_CR1_UE | USART_CR1_TE;
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
