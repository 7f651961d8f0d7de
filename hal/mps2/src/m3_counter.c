/* A decimal through semihosting, and the SysTick counter of hal_mps2/m3.h. */
#include "hal_mps2/m3.h"

void m3_put_int(long long v)
{
    char buf[24];
    int n = sizeof buf;
    buf[--n] = 0;
    unsigned long long u = v < 0 ? 0ull - (unsigned long long)v : (unsigned long long)v;
    do {
        buf[--n] = (char)('0' + u % 10u);
        u /= 10u;
    } while (u);
    if (v < 0)
        buf[--n] = '-';
    m3_puts(buf + n);
}

/* SysTick: CSR, RVR, CVR (ARMv7-M B3.3). */
#define SYST_CSR (*(volatile uint32_t *)0xE000E010u)
#define SYST_RVR (*(volatile uint32_t *)0xE000E014u)
#define SYST_CVR (*(volatile uint32_t *)0xE000E018u)

void m3_counter_start(void)
{
    SYST_CSR = 0;
    SYST_RVR = 0x00FFFFFFu;
    SYST_CVR = 0;
    SYST_CSR = 5u; /* enabled, core clock, no interrupt */
}

uint32_t m3_cycles(void)
{
    return (0x00FFFFFFu - SYST_CVR) & 0x00FFFFFFu;
}
