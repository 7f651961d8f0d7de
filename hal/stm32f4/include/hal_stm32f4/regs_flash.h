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

/* KEYR: the two keys, in this order, unlock CR (RM0090 3.5.1) */
#define FLASH_KEY1 0x45670123u
#define FLASH_KEY2 0xCDEF89ABu

/* SR (RM0090 3.9.4): error flags and EOP are cleared by writing 1 */
#define FLASH_SR_EOP (1u << 0)
#define FLASH_SR_OPERR (1u << 1)
#define FLASH_SR_WRPERR (1u << 4)
#define FLASH_SR_PGAERR (1u << 5)
#define FLASH_SR_PGPERR (1u << 6)
#define FLASH_SR_PGSERR (1u << 7)
#define FLASH_SR_BSY (1u << 16)

/* CR (RM0090 3.9.5) */
#define FLASH_CR_PG (1u << 0)
#define FLASH_CR_SER (1u << 1)
#define FLASH_CR_SNB(n) ((uint32_t)(n) << 3) /* sector number, bits 6:3 on the F405/407 */
#define FLASH_CR_PSIZE_X32 (2u << 8)        /* 32-bit parallelism: 2.7..3.6 V */
#define FLASH_CR_STRT (1u << 16)
#define FLASH_CR_LOCK (1u << 31)

#endif
