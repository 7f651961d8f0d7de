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

/* The linker's section bounds come in as arguments: within one function they are pointers to
 * different objects, whose comparison C does not define (and static analysis flags). */
static void copy_words(uint32_t *dst, const uint32_t *src, const uint32_t *end)
{
    while (dst < end)
        *dst++ = *src++;
}

static void zero_words(uint32_t *dst, const uint32_t *end)
{
    while (dst < end)
        *dst++ = 0;
}

void Reset_Handler(void)
{
    copy_words(&_sdata, &_sidata, &_edata);
    zero_words(&_sbss, &_ebss);
    m3_exit(main());
}

void Fault_Handler(void)
{
    m3_puts("fault: an exception the image does not handle\n");
    m3_exit(1);
}
