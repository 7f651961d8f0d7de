/* External interrupts, system configuration, independent watchdog and the debug freeze of the
 * STM32F405/407 (RM0090 sections 12, 9, 19 and 38). */
#ifndef TSE_REGS_MISC_H
#define TSE_REGS_MISC_H

#include <stddef.h>
#include <stdint.h>

typedef struct {
    volatile uint32_t IMR;   /* 0x00 */
    volatile uint32_t EMR;   /* 0x04 */
    volatile uint32_t RTSR;  /* 0x08 */
    volatile uint32_t FTSR;  /* 0x0C */
    volatile uint32_t SWIER; /* 0x10 */
    volatile uint32_t PR;    /* 0x14: write 1 to clear */
} tse_exti_regs;

#define TSE_EXTI ((tse_exti_regs *)0x40013C00u)

typedef struct {
    volatile uint32_t MEMRMP;    /* 0x00 */
    volatile uint32_t PMC;       /* 0x04 */
    volatile uint32_t EXTICR[4]; /* 0x08..0x14: 4 bits a line, 0 = port A, 1 = B, 2 = C */
    uint32_t r0[2];
    volatile uint32_t CMPCR;     /* 0x20 */
} tse_syscfg_regs;

_Static_assert(offsetof(tse_syscfg_regs, CMPCR) == 0x20, "SYSCFG CMPCR offset");

#define TSE_SYSCFG ((tse_syscfg_regs *)0x40013800u)

typedef struct {
    volatile uint32_t KR;  /* 0x00 */
    volatile uint32_t PR;  /* 0x04 */
    volatile uint32_t RLR; /* 0x08 */
    volatile uint32_t SR;  /* 0x0C */
} tse_iwdg_regs;

#define TSE_IWDG ((tse_iwdg_regs *)0x40003000u)
#define IWDG_KEY_START 0xCCCCu
#define IWDG_KEY_RELOAD 0xAAAAu
#define IWDG_KEY_UNLOCK 0x5555u
#define IWDG_SR_PVU (1u << 0)
#define IWDG_SR_RVU (1u << 1)

/* DBGMCU: stop the watchdog while a debugger halts the core. */
#define TSE_DBGMCU_APB1_FZ (*(volatile uint32_t *)0xE0042008u)
#define DBGMCU_IWDG_STOP (1u << 12)

#endif
