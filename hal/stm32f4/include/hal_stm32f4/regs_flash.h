/* Embedded flash interface of the STM32F405/407 (RM0090 section 3.9), our own definitions. */
#ifndef TSE_REGS_FLASH_H
#define TSE_REGS_FLASH_H

#include <stddef.h>
#include <stdint.h>

#define TSE_FLASH_BASE 0x40023C00u

typedef struct {
    volatile uint32_t ACR;     /* 0x00 access control: latency, prefetch, caches */
    volatile uint32_t KEYR;    /* 0x04 */
    volatile uint32_t OPTKEYR; /* 0x08 */
    volatile uint32_t SR;      /* 0x0C */
    volatile uint32_t CR;      /* 0x10 */
    volatile uint32_t OPTCR;   /* 0x14 */
} tse_flash_regs;

_Static_assert(offsetof(tse_flash_regs, SR) == 0x0C, "FLASH SR offset");
_Static_assert(offsetof(tse_flash_regs, OPTCR) == 0x14, "FLASH OPTCR offset");

#define TSE_FLASH ((tse_flash_regs *)TSE_FLASH_BASE)

/* ACR */
#define FLASH_ACR_LATENCY_MASK 0x7u
#define FLASH_ACR_PRFTEN (1u << 8)
#define FLASH_ACR_ICEN (1u << 9)
#define FLASH_ACR_DCEN (1u << 10)
#define FLASH_ACR_ICRST (1u << 11)
#define FLASH_ACR_DCRST (1u << 12)

#endif
