/* The Cortex-M3 test and benchmark platform: QEMU's mps2-an385, semihosting for output, SysTick
 * as an instruction counter.  Integers only (the Cortex-M3 build has no floating point at all,
 * so no printf either: m3_put_* format what the images print).  Test and benchmark images only. */
#ifndef HAL_MPS2_M3_H
#define HAL_MPS2_M3_H

#include <stdint.h>

/* Semihosting (the STM32F4's calls, hal_stm32f4/semihost.h): a string, a signed decimal, and the
 * end (0: success).  sh_printf is not for these images: newlib's printf is not integer-only. */
#include "hal_stm32f4/semihost.h"
#define m3_puts sh_puts
#define m3_exit sh_exit
void m3_put_int(long long v);

/* SysTick running from the core clock, counting down through 24 bits: with QEMU's -icount
 * shift=N each instruction advances the clock by 2^N ns, and the core clock of the mps2-an385 is
 * 25 MHz, so an instruction is 2^N / 40 counts (shift=6: 1.6).  m3_cycles() is the elapsed count,
 * modulo 2^24, increasing. */
void m3_counter_start(void);
uint32_t m3_cycles(void);

#endif
