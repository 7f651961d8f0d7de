/* The F405/407 flash controller as flash_ops (hal_stm32f4/flash_f4.h). */
#include "hal_stm32f4/flash_f4.h"

#include "hal_stm32f4/board_desc.h"
#include "hal_stm32f4/regs_dwt.h"
#include "hal_stm32f4/regs_flash.h"
#include "hal_stm32f4/regs_misc.h"

/* Runs from RAM; called from flash through a full address (RAM is out of reach of a BL). */
#define RAMFUNC __attribute__((section(".ramfunc"), noinline, long_call))

#define SR_ERRORS \
    (FLASH_SR_OPERR | FLASH_SR_WRPERR | FLASH_SR_PGAERR | FLASH_SR_PGPERR | FLASH_SR_PGSERR)

/* The bounds of flash_f4.h, from the datasheet's flash programming characteristics. */
#define ERASE_BOUND_MS 4000u
#define PROGRAM_BOUND_US 1000u

#define FASTEST_HZ 168000000u
#define ERASE_CYCLES (FASTEST_HZ / 1000u * ERASE_BOUND_MS)
#define PROGRAM_CYCLES (FASTEST_HZ / 1000000u * PROGRAM_BOUND_US)

/* In RAM (.bss): read by the routines while the flash is busy. */
static struct {
    void (*idle)(void);
    uint32_t last_error;
} state;

/* The log's two sectors, the description's param_sector and the next (board_desc.h; two of the
 * same size, above the image: the host checker, tests/boards, holds every description to it). */
static uint32_t log_base(void)
{
    return board_sector_addr(tse_board_desc.param_sector);
}

static uint32_t log_sector_bytes(void)
{
    return board_sector_bytes(tse_board_desc.param_sector);
}

void flash_f4_feed_iwdg(void)
{
    TSE_IWDG->KR = IWDG_KEY_RELOAD;
}

/* Until BSY clears, at most `cycles` core cycles and `cycles` polls (flash_f4.h). */
static RAMFUNC int wait_ready(uint32_t cycles, void (*idle)(void))
{
    const uint32_t start = TSE_DWT->CYCCNT;
    for (uint32_t polls = 0; (TSE_FLASH->SR & FLASH_SR_BSY) != 0; ++polls) {
        if (TSE_DWT->CYCCNT - start > cycles || polls > cycles)
            return FLASH_OPS_ETIMEOUT;
        if (idle)
            idle();
    }
    return FLASH_OPS_OK;
}

/* Clears stale flags (PGSERR and PGPERR can be set from reset on) and unlocks CR: the keys
 * only when it is locked, since a key written to an unlocked CR locks it until reset. */
static RAMFUNC int unlock(void)
{
    TSE_FLASH->SR = SR_ERRORS | FLASH_SR_EOP;
    if ((TSE_FLASH->CR & FLASH_CR_LOCK) != 0) {
        TSE_FLASH->KEYR = FLASH_KEY1;
        TSE_FLASH->KEYR = FLASH_KEY2;
    }
    return (TSE_FLASH->CR & FLASH_CR_LOCK) != 0 ? FLASH_OPS_EFAIL : FLASH_OPS_OK;
}

/* The D-cache keeps lines read before the erase or program and is not told of either: reset
 * it (DCRST may only be written while the cache is off). */
static RAMFUNC void reset_data_cache(void)
{
    const uint32_t acr = TSE_FLASH->ACR & ~FLASH_ACR_DCRST;
    TSE_FLASH->ACR = acr & ~FLASH_ACR_DCEN;
    TSE_FLASH->ACR = (acr & ~FLASH_ACR_DCEN) | FLASH_ACR_DCRST;
    TSE_FLASH->ACR = acr & ~FLASH_ACR_DCEN;
    TSE_FLASH->ACR = acr;
}

/* Locks CR (clearing PG, SER, SNB), reads the outcome, clears the flags. */
static RAMFUNC int finish(void)
{
    const uint32_t sr = TSE_FLASH->SR;
    TSE_FLASH->CR = FLASH_CR_LOCK;
    TSE_FLASH->SR = SR_ERRORS | FLASH_SR_EOP;
    reset_data_cache();
    if ((sr & SR_ERRORS) != 0) {
        state.last_error = sr & SR_ERRORS;
        return FLASH_OPS_EFAIL;
    }
    return FLASH_OPS_OK;
}

static RAMFUNC int erase_sector(uint32_t snb)
{
    int rc = wait_ready(ERASE_CYCLES, state.idle);
    if (rc != FLASH_OPS_OK)
        return rc;
    rc = unlock();
    if (rc != FLASH_OPS_OK)
        return rc;
    uint32_t primask;
    __asm__ volatile("mrs %0, primask\n\tcpsid i" : "=r"(primask)::"memory");
    TSE_FLASH->CR = FLASH_CR_PSIZE_X32 | FLASH_CR_SER | FLASH_CR_SNB(snb);
    TSE_FLASH->CR |= FLASH_CR_STRT;
    rc = wait_ready(ERASE_CYCLES, state.idle);
    if (rc == FLASH_OPS_OK)
        rc = finish();
    __asm__ volatile("msr primask, %0" ::"r"(primask) : "memory");
    return rc;
}

static RAMFUNC int program_words(volatile uint32_t *dst, const uint32_t *src, uint32_t n)
{
    /* Before the first word whatever came before may still be running: allow an erase. */
    int rc = wait_ready(ERASE_CYCLES, state.idle);
    if (rc != FLASH_OPS_OK)
        return rc;
    rc = unlock();
    if (rc != FLASH_OPS_OK)
        return rc;
    TSE_FLASH->CR = FLASH_CR_PSIZE_X32 | FLASH_CR_PG;
    for (uint32_t k = 0; k < n; ++k) {
        dst[k] = src[k]; /* a word store: the access size PSIZE x32 requires */
        __asm__ volatile("dsb" ::: "memory"); /* the store reaches the controller before the poll */
        rc = wait_ready(PROGRAM_CYCLES, state.idle);
        if (rc != FLASH_OPS_OK)
            return rc;
        if ((TSE_FLASH->SR & SR_ERRORS) != 0)
            break;
    }
    return finish();
}

/* From here on, code in flash: nothing runs while the controller is busy. */

static void cycle_counter_on(void)
{
    TSE_DEMCR |= DEMCR_TRCENA;
    TSE_DWT->CTRL |= DWT_CTRL_CYCCNTENA;
}

static int f4_erase(void *ctx, uint32_t sector)
{
    (void)ctx;
    if (sector > 1u)
        return FLASH_OPS_EARG;
    cycle_counter_on();
    return erase_sector(tse_board_desc.param_sector + sector);
}

static int f4_program(void *ctx, uint32_t offset, const uint32_t *words, uint32_t n)
{
    (void)ctx;
    const uint32_t region = 2u * log_sector_bytes();
    if (offset % 4u != 0 || offset > region || n > (region - offset) / 4u)
        return FLASH_OPS_EARG;
    if (n == 0)
        return FLASH_OPS_OK;
    cycle_counter_on();
    return program_words((volatile uint32_t *)(log_base() + offset), words, n);
}

flash_ops flash_f4_ops(void (*idle)(void))
{
    state.idle = idle;
    return (flash_ops){&state, (const uint32_t *)log_base(), log_sector_bytes(), f4_erase, f4_program};
}

/* The whole device for the bootloader (flash_f4.h): sectors first .. end - 1 only. */
#define DEVICE_BASE 0x08000000u
static struct {
    uint32_t first, end;
} device;

static uint32_t sector_start(uint32_t k)
{
    /* RM0090 table 5: four of 16 KiB, one of 64 KiB, then 128 KiB each. */
    return k <= 4u ? k * 0x4000u : 0x20000u * (k - 4u);
}

static int dev_erase(void *ctx, uint32_t sector)
{
    (void)ctx;
    if (sector < device.first || sector >= device.end)
        return FLASH_OPS_EARG;
    cycle_counter_on();
    return erase_sector(sector);
}

static int dev_program(void *ctx, uint32_t offset, const uint32_t *words, uint32_t n)
{
    (void)ctx;
    const uint32_t lo = sector_start(device.first), hi = sector_start(device.end);
    if (offset % 4u != 0 || offset < lo || offset > hi || n > (hi - offset) / 4u)
        return FLASH_OPS_EARG;
    if (n == 0)
        return FLASH_OPS_OK;
    cycle_counter_on();
    return program_words((volatile uint32_t *)(DEVICE_BASE + offset), words, n);
}

flash_ops flash_f4_device_ops(void (*idle)(void), uint32_t first, uint32_t end)
{
    state.idle = idle;
    device.first = first;
    device.end = end <= 12u ? end : 12u;
    return (flash_ops){&device, (const uint32_t *)DEVICE_BASE, 0, dev_erase, dev_program};
}

uint32_t flash_f4_last_error(void)
{
    return state.last_error;
}
