/* The reset handler's promises, checked on the emulated core: initialised data copied from
 * flash, zero-initialised data zero, the FPU usable, the stack at the bottom of SRAM (so that an
 * overflow faults), divide-by-zero trapping enabled, the fault exceptions enabled. */
#include <stdint.h>

#include "hal_stm32f4/regs_core.h"
#include "target_test.h"

static volatile uint32_t initialised[4] = {0xDEADBEEFu, 1u, 2u, 0x12345678u};
static volatile uint32_t zeroed[64];
static volatile float operand = 3.0f;
extern uint32_t _sstack, _estack;

static void data_copied(void)
{
    TT_CHECK(initialised[0] == 0xDEADBEEFu);
    TT_CHECK(initialised[3] == 0x12345678u);
}

static void bss_zeroed(void)
{
    uint32_t any = 0;
    for (unsigned i = 0; i < 64; ++i)
        any |= zeroed[i];
    TT_CHECK(any == 0);
}

static void fpu_on(void)
{
    TT_CHECK((TSE_CPACR & CPACR_CP10_CP11_FULL) == CPACR_CP10_CP11_FULL);
    const float x = operand * operand + 0.5f; /* vmul/vadd: would fault with the FPU off */
    TT_CHECK(x == 9.5f);
    volatile float r = __builtin_sqrtf(operand * 12.0f);
    TT_CHECK(r == 6.0f);
}

static void stack_at_bottom(void)
{
    volatile uint32_t here = 0;
    const uintptr_t a = (uintptr_t)&here;
    TT_CHECKF(a >= (uintptr_t)&_sstack && a < (uintptr_t)&_estack, "stack variable at %08lx\n", (unsigned long)a);
    TT_CHECK((uintptr_t)&_sstack == 0x20000000u);
}

static void traps_enabled(void)
{
    TT_CHECK(TSE_SCB->CCR & SCB_CCR_DIV_0_TRP);
    const uint32_t want = SCB_SHCSR_MEMFAULTENA | SCB_SHCSR_BUSFAULTENA | SCB_SHCSR_USGFAULTENA;
    TT_CHECK((TSE_SCB->SHCSR & want) == want);
}

int main(void)
{
    tt_begin("startup");
    tt_case("data copied from flash", data_copied);
    tt_case("bss zeroed", bss_zeroed);
    tt_case("FPU enabled before main", fpu_on);
    tt_case("stack at the bottom of SRAM", stack_at_bottom);
    tt_case("fault traps enabled", traps_enabled);
    tt_finish();
}
