/* The USARTs of the STM32F405/407 (RM0090 section 30.6), our own definitions: only what the boot
 * line uses. */
#ifndef TSE_REGS_USART_H
#define TSE_REGS_USART_H

#include <stddef.h>
#include <stdint.h>

typedef struct {
    volatile uint32_t SR;   /* 0x00 */
    volatile uint32_t DR;   /* 0x04 */
    volatile uint32_t BRR;  /* 0x08 */
    volatile uint32_t CR1;  /* 0x0C */
    volatile uint32_t CR2;  /* 0x10 */
    volatile uint32_t CR3;  /* 0x14 */
    volatile uint32_t GTPR; /* 0x18 */
} tse_usart_regs;

_Static_assert(offsetof(tse_usart_regs, CR1) == 0x0C, "USART CR1 offset");

#define TSE_USART1 ((tse_usart_regs *)0x40011000u) /* APB2 */
#define TSE_USART2 ((tse_usart_regs *)0x40004400u) /* APB1 */
#define TSE_USART3 ((tse_usart_regs *)0x40004800u) /* APB1 */
#define TSE_USART6 ((tse_usart_regs *)0x40011400u) /* APB2 */

#define USART_SR_TC (1u << 6)
#define USART_SR_TXE (1u << 7)
#define USART_CR1_TE (1u << 3)
#define USART_CR1_UE (1u << 13)

#endif
