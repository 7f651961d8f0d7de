/* The flash controller of the STM32F405/407 as flash_ops over the parameter log's sectors
 * (10 and 11, param_log.h).  Register level, board build only.  There is one controller: the
 * ops share one state.
 *
 * What it does (RM0090 3.5): unlock (KEYR), sector erase (SER, SNB, STRT) or word program (PG)
 * at 32-bit parallelism (PSIZE x32, for 2.7..3.6 V), wait for BSY, check and clear the error
 * flags (OPERR, WRPERR, PGAERR, PGPERR, PGSERR), lock again, and reset the ART data cache so
 * that reads see the new contents.
 *
 * Every wait on BSY is bounded by time, read from the core's cycle counter (regs_dwt.h):
 * - erase: 4 s.  Datasheet (DS8626, flash programming characteristics): a 128 KiB sector takes
 *   1 s typical, 2 s at most at x32 parallelism, and at most 4 s at x8; 4 s is twice our
 *   worst case.
 * - program: 1 ms a word.  Datasheet: 16 us typical, 100 us at most.
 * The bounds are counted in cycles of the fastest clock, 168 MHz: on a slower clock (the
 * 16 MHz fallback of clock.h) they last longer, never shorter.  A wait also stops after as
 * many polls as its bound has cycles (a poll takes at least one), so a stopped counter cannot
 * make it endless.  Each poll calls `idle`.
 *
 * The CPU stalls on any fetch from flash while an erase or program runs (the F405 has a
 * single bank).  Hence:
 * - the erase and program routines and their waits run from RAM (section .ramfunc, which the
 *   linker script copies to RAM with .data);
 * - `idle` must run from RAM too and touch no flash, or the erase stalls it and the watchdog
 *   starves: flash_f4_feed_iwdg is such a function (board_iwdg_feed, in flash, is not);
 * - interrupts are masked (PRIMASK) for the whole erase, by the erase routine itself since its
 *   caller (the log) is plain C: the vector table and the handlers are in flash, so an
 *   interrupt taken then would stall the CPU until the erase ends (up to 2 s) with no way to
 *   feed the watchdog.  The board must therefore only save parameters when an interrupt
 *   delayed by 2 s is harmless (drives disabled); a program stalls them 100 us at most.
 * A wait that times out returns with the controller still busy and unlocked: CR cannot be
 * written while BSY is set (the write would stall the bus until it clears). */
#ifndef TSE_BOARD_FLASH_F4_H
#define TSE_BOARD_FLASH_F4_H

#include <stdint.h>

#include "hal_stm32f4/flash_ops.h"

/* The ops over the description's two log sectors, contents read where they lie.  idle (may be NULL)
 * is called on every poll of a wait and must live in .ramfunc. */
flash_ops flash_f4_ops(void (*idle)(void));

/* The ops over the whole flash from 0x08000000, for the bootloader's update (boot/layout.h):
 * erase(k) erases sector k, program takes offsets from 0x08000000; both only within sectors
 * first .. end - 1 (the application area), anything else FLASH_OPS_EARG: the bootloader's own
 * sectors and the parameter log cannot be touched through them, whatever the caller asks. */
flash_ops flash_f4_device_ops(void (*idle)(void), uint32_t first, uint32_t end);

/* The SR error flags of the last operation that failed on them, 0 if none has. */
uint32_t flash_f4_last_error(void);

/* Reloads the independent watchdog; lives in RAM, for use as `idle`. */
void flash_f4_feed_iwdg(void) __attribute__((section(".ramfunc"), noinline, long_call));

#endif
