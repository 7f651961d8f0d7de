/* Cortex-M4 core peripherals (ARMv7-M architecture reference, Cortex-M4 generic user guide):
 * system control block, NVIC, SysTick, FPU access.  Our own definitions. */
#ifndef TSE_REGS_CORE_H
#define TSE_REGS_CORE_H

#include <stddef.h>
#include <stdint.h>

typedef struct {
    volatile uint32_t CPUID; /* 0x00 */
    volatile uint32_t ICSR;  /* 0x04 */
    volatile uint32_t VTOR;  /* 0x08 */
    volatile uint32_t AIRCR; /* 0x0C */
    volatile uint32_t SCR;   /* 0x10 */
    volatile uint32_t CCR;   /* 0x14 */
    volatile uint8_t SHPR[12]; /* 0x18 system handler priorities, handlers 4..15 */
    volatile uint32_t SHCSR; /* 0x24 */
    volatile uint32_t CFSR;  /* 0x28 configurable fault status (MMFSR, BFSR, UFSR) */
    volatile uint32_t HFSR;  /* 0x2C */
    volatile uint32_t DFSR;  /* 0x30 */
    volatile uint32_t MMFAR; /* 0x34 */
    volatile uint32_t BFAR;  /* 0x38 */
    volatile uint32_t AFSR;  /* 0x3C */
} tse_scb_regs;

_Static_assert(offsetof(tse_scb_regs, SHCSR) == 0x24, "SCB SHCSR offset");
_Static_assert(offsetof(tse_scb_regs, AFSR) == 0x3C, "SCB AFSR offset");

#define TSE_SCB ((tse_scb_regs *)0xE000ED00u)
#define TSE_CPACR (*(volatile uint32_t *)0xE000ED88u)
#define TSE_FPCCR (*(volatile uint32_t *)0xE000EF34u)
#define CPACR_CP10_CP11_FULL (0xFu << 20)
#define SCB_AIRCR_VECTKEY (0x05FAu << 16)
#define SCB_AIRCR_SYSRESETREQ (1u << 2)
#define SCB_CCR_DIV_0_TRP (1u << 4)
#define SCB_SHCSR_MEMFAULTENA (1u << 16)
#define SCB_SHCSR_BUSFAULTENA (1u << 17)
#define SCB_SHCSR_USGFAULTENA (1u << 18)

typedef struct {
    volatile uint32_t ISER[8]; /* 0xE000E100 */
    uint32_t r0[24];
    volatile uint32_t ICER[8]; /* 0xE000E180 */
    uint32_t r1[24];
    volatile uint32_t ISPR[8]; /* 0xE000E200 */
    uint32_t r2[24];
    volatile uint32_t ICPR[8]; /* 0xE000E280 */
    uint32_t r3[24];
    volatile uint32_t IABR[8]; /* 0xE000E300 */
    uint32_t r4[56];
    volatile uint8_t IPR[240]; /* 0xE000E400, one byte per interrupt, top 4 bits implemented */
} tse_nvic_regs;

_Static_assert(offsetof(tse_nvic_regs, ICER) == 0x80, "NVIC ICER offset");
_Static_assert(offsetof(tse_nvic_regs, IPR) == 0x300, "NVIC IPR offset");

#define TSE_NVIC ((tse_nvic_regs *)0xE000E100u)

typedef struct {
    volatile uint32_t CTRL;  /* 0x00 */
    volatile uint32_t LOAD;  /* 0x04 */
    volatile uint32_t VAL;   /* 0x08 */
    volatile uint32_t CALIB; /* 0x0C */
} tse_systick_regs;

#define TSE_SYSTICK ((tse_systick_regs *)0xE000E010u)

/* The STM32F4 implements 4 priority bits: priority p sits in the top nibble. */
static inline void tse_nvic_enable(unsigned irq, unsigned priority)
{
    TSE_NVIC->IPR[irq] = (uint8_t)(priority << 4);
    TSE_NVIC->ICPR[irq >> 5] = 1u << (irq & 31u);
    TSE_NVIC->ISER[irq >> 5] = 1u << (irq & 31u);
}

static inline void tse_nvic_disable(unsigned irq)
{
    TSE_NVIC->ICER[irq >> 5] = 1u << (irq & 31u);
    __asm__ volatile("dsb\n\tisb" ::: "memory");
}

static inline void tse_irq_disable(void)
{
    __asm__ volatile("cpsid i" ::: "memory");
}

static inline void tse_irq_enable(void)
{
    __asm__ volatile("cpsie i" ::: "memory");
}

/* Masks the interrupts of priority `priority` and below (numerically >= it) until restored, leaving
 * the more urgent ones running; never lowers a mask already higher.  Returns what to restore. */
static inline uint32_t tse_basepri_raise(unsigned priority)
{
    uint32_t saved;
    __asm__ volatile("mrs %0, basepri" : "=r"(saved)::"memory");
    const uint32_t mask = (uint32_t)(priority << 4);
    __asm__ volatile("msr basepri_max, %0" ::"r"(mask) : "memory");
    return saved;
}

static inline void tse_basepri_restore(uint32_t saved)
{
    __asm__ volatile("msr basepri, %0" ::"r"(saved) : "memory");
}

/* Interrupt numbers of the STM32F405/407 (RM0090 table 61) that the board uses. */
enum {
    IRQ_EXTI0 = 6, /* EXTI1..4: 7..10 */
    IRQ_EXTI9_5 = 23,
    IRQ_EXTI15_10 = 40,
    IRQ_CAN1_TX = 19,
    IRQ_CAN1_RX0 = 20,
    IRQ_CAN1_RX1 = 21,
    IRQ_CAN1_SCE = 22,
    IRQ_TIM2 = 28,
    IRQ_TIM3 = 29,
    IRQ_TIM4 = 30,
    IRQ_TIM5 = 50,
    IRQ_COUNT = 82
};

#endif
