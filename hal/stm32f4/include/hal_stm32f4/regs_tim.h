/* General-purpose timers TIM2..TIM5 of the STM32F405/407 (RM0090 section 18). */
#ifndef TSE_REGS_TIM_H
#define TSE_REGS_TIM_H

#include <stddef.h>
#include <stdint.h>

typedef struct {
    volatile uint32_t CR1;   /* 0x00 */
    volatile uint32_t CR2;   /* 0x04 */
    volatile uint32_t SMCR;  /* 0x08 */
    volatile uint32_t DIER;  /* 0x0C */
    volatile uint32_t SR;    /* 0x10 */
    volatile uint32_t EGR;   /* 0x14 */
    volatile uint32_t CCMR1; /* 0x18 */
    volatile uint32_t CCMR2; /* 0x1C */
    volatile uint32_t CCER;  /* 0x20 */
    volatile uint32_t CNT;   /* 0x24 */
    volatile uint32_t PSC;   /* 0x28 */
    volatile uint32_t ARR;   /* 0x2C */
    volatile uint32_t RCR;   /* 0x30 */
    volatile uint32_t CCR1;  /* 0x34 */
    volatile uint32_t CCR2;  /* 0x38 */
    volatile uint32_t CCR3;  /* 0x3C */
    volatile uint32_t CCR4;  /* 0x40 */
} tse_tim_regs;

_Static_assert(offsetof(tse_tim_regs, CNT) == 0x24, "TIM CNT offset");
_Static_assert(offsetof(tse_tim_regs, CCR1) == 0x34, "TIM CCR1 offset");

#define TSE_TIM2 ((tse_tim_regs *)0x40000000u)
#define TSE_TIM3 ((tse_tim_regs *)0x40000400u)
#define TSE_TIM4 ((tse_tim_regs *)0x40000800u)
#define TSE_TIM5 ((tse_tim_regs *)0x40000C00u)

#define TIM_CR1_CEN (1u << 0)
#define TIM_CR1_URS (1u << 2)
#define TIM_CR1_OPM (1u << 3)
#define TIM_CR1_ARPE (1u << 7)
#define TIM_DIER_UIE (1u << 0)
#define TIM_DIER_CC1IE (1u << 1)
#define TIM_SR_UIF (1u << 0)
#define TIM_SR_CC1IF (1u << 1)
#define TIM_EGR_UG (1u << 0)

#endif
