/* Reset and exception entry on the Cortex-M3 (QEMU mps2-an385): the vector table, .data copied
 * and .bss zeroed, main, and its return value to the host through semihosting; a fault ends the
 * run with a failure. */
#include <stdint.h>

#include "hal_mps2/m3.h"

/* The linker script's names (hal/mps2/ld/mps2_an385.ld).
 * NOLINTNEXTLINE(bugprone-reserved-identifier) */
extern uint32_t _sidata, _sdata, _edata, _sbss, _ebss, _estack;
int main(void);

void Reset_Handler(void);
void Fault_Handler(void);

typedef void (*vector)(void);

__attribute__((section(".isr_vector"), used)) static const vector vectors[16] = {
    (vector)(uintptr_t)&_estack, Reset_Handler, Fault_Handler, Fault_Handler, Fault_Handler, Fault_Handler,
    Fault_Handler, 0, 0, 0, 0, Fault_Handler, Fault_Handler, 0, Fault_Handler, Fault_Handler,
};

void Reset_Handler(void)
{
    const uint32_t *src = &_sidata;
    for (uint32_t *dst = &_sdata; dst < &_edata;)
        *dst++ = *src++;
    for (uint32_t *dst = &_sbss; dst < &_ebss;)
        *dst++ = 0;
    m3_exit(main());
}

void Fault_Handler(void)
{
    m3_puts("fault: an exception the image does not handle\n");
    m3_exit(1);
}
