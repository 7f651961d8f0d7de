/* The Cortex-M4's cycle counter: DWT_CTRL and DWT_CYCCNT (ARMv7-M architecture reference
 * manual C1.8) and the trace enable in DEMCR (C1.6.5).  Our own definitions.
 *
 * QEMU (7.2) maps nothing there: reads return 0, so the counter stands still under
 * emulation. */
#ifndef TSE_REGS_DWT_H
#define TSE_REGS_DWT_H

#include <stddef.h>
#include <stdint.h>

typedef struct {
    volatile uint32_t CTRL;   /* 0x00 */
    volatile uint32_t CYCCNT; /* 0x04: core clock cycles, wraps at 2^32 */
} tse_dwt_regs;

_Static_assert(offsetof(tse_dwt_regs, CYCCNT) == 0x04, "DWT CYCCNT offset");

#define TSE_DWT ((tse_dwt_regs *)0xE0001000u)
#define DWT_CTRL_CYCCNTENA (1u << 0)

#define TSE_DEMCR (*(volatile uint32_t *)0xE000EDFCu)
#define DEMCR_TRCENA (1u << 24) /* powers the DWT */

#endif
