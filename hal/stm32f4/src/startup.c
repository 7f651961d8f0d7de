/* Reset and exception entry of the STM32F405/407: the vector table, the reset handler (FPU on,
 * .data and .ramfunc copied, .bss zeroed, then main), and the fault handlers. */
#include <stdint.h>
#include <string.h>

#include "hal_stm32f4/fault.h"
#include "hal_stm32f4/regs_core.h"

/* The linker script's names, reserved identifiers by the GNU convention.
 * NOLINTNEXTLINE(bugprone-reserved-identifier) */
extern uint32_t _sidata, _sdata, _edata, _sbss, _ebss, _estack;
int main(void);

void Reset_Handler(void);
void Default_Handler(void);
void HardFault_Handler(void);

/* Handlers the board may define; the others fall to Default_Handler. */
#define WEAK_DEFAULT __attribute__((weak, alias("Default_Handler")))
void NMI_Handler(void) WEAK_DEFAULT;
void MemManage_Handler(void) __attribute__((weak, alias("HardFault_Handler")));
void BusFault_Handler(void) __attribute__((weak, alias("HardFault_Handler")));
void UsageFault_Handler(void) __attribute__((weak, alias("HardFault_Handler")));
void SVC_Handler(void) WEAK_DEFAULT;
void DebugMon_Handler(void) WEAK_DEFAULT;
void PendSV_Handler(void) WEAK_DEFAULT;
void SysTick_Handler(void) WEAK_DEFAULT;
void EXTI0_IRQHandler(void) WEAK_DEFAULT;
void EXTI1_IRQHandler(void) WEAK_DEFAULT;
void EXTI2_IRQHandler(void) WEAK_DEFAULT;
void EXTI3_IRQHandler(void) WEAK_DEFAULT;
void EXTI4_IRQHandler(void) WEAK_DEFAULT;
void EXTI9_5_IRQHandler(void) WEAK_DEFAULT;
void EXTI15_10_IRQHandler(void) WEAK_DEFAULT;
void CAN1_TX_IRQHandler(void) WEAK_DEFAULT;
void CAN1_RX0_IRQHandler(void) WEAK_DEFAULT;
void CAN1_RX1_IRQHandler(void) WEAK_DEFAULT;
void CAN1_SCE_IRQHandler(void) WEAK_DEFAULT;
void TIM2_IRQHandler(void) WEAK_DEFAULT;
void TIM3_IRQHandler(void) WEAK_DEFAULT;
void TIM4_IRQHandler(void) WEAK_DEFAULT;
void TIM5_IRQHandler(void) WEAK_DEFAULT;

typedef void (*vector)(void);

/* 16 core exceptions, then the 82 interrupts of RM0090 table 61 in order; an interrupt the
 * board does not handle goes to Default_Handler, which records it and stops the outputs. */
#define D Default_Handler
__attribute__((section(".isr_vector"), used)) static const vector vectors[16 + IRQ_COUNT] = {
    (vector)(uintptr_t)&_estack, /* 0 */
    Reset_Handler, /* 1 */
    NMI_Handler, /* 2 */
    HardFault_Handler, /* 3 */
    MemManage_Handler, /* 4 */
    BusFault_Handler, /* 5 */
    UsageFault_Handler, /* 6 */
    0, /* 7 */
    0, /* 8 */
    0, /* 9 */
    0, /* 10 */
    SVC_Handler, /* 11 */
    DebugMon_Handler, /* 12 */
    0, /* 13 */
    PendSV_Handler, /* 14 */
    SysTick_Handler, /* 15 */
    D, D, D, D, D, D, EXTI0_IRQHandler, EXTI1_IRQHandler, /* IRQ 0.. */
    EXTI2_IRQHandler, EXTI3_IRQHandler, EXTI4_IRQHandler, D, D, D, D, D, /* IRQ 8.. */
    D, D, D, CAN1_TX_IRQHandler, CAN1_RX0_IRQHandler, CAN1_RX1_IRQHandler, CAN1_SCE_IRQHandler, EXTI9_5_IRQHandler, /* IRQ 16.. */
    D, D, D, D, TIM2_IRQHandler, TIM3_IRQHandler, TIM4_IRQHandler, D, /* IRQ 24.. */
    D, D, D, D, D, D, D, D, /* IRQ 32.. */
    EXTI15_10_IRQHandler, D, D, D, D, D, D, D, /* IRQ 40.. */
    D, D, TIM5_IRQHandler, D, D, D, D, D, /* IRQ 48.. */
    D, D, D, D, D, D, D, D, /* IRQ 56.. */
    D, D, D, D, D, D, D, D, /* IRQ 64.. */
    D, D, D, D, D, D, D, D, /* IRQ 72.. */
    D, D, /* IRQ 80.. */
};
#undef D

/* Plain loops rather than memcpy/memset, which need not be safe before the FPU is on and .data
 * exists; the attribute keeps GCC from turning the loops back into those calls. */
#define NO_LIBCALLS __attribute__((optimize("no-tree-loop-distribute-patterns")))
NO_LIBCALLS static void copy_words(uint32_t *dst, const uint32_t *src, const uint32_t *end)
{
    while (dst < end)
        *dst++ = *src++;
}

NO_LIBCALLS static void zero_words(uint32_t *dst, const uint32_t *end)
{
    while (dst < end)
        *dst++ = 0;
}

/* Which stack the exception frame is on: EXC_RETURN bit 2 in lr. */
__attribute__((naked)) void HardFault_Handler(void)
{
    __asm__ volatile("tst lr, #4\n\t"
                     "ite eq\n\t"
                     "mrseq r0, msp\n\t"
                     "mrsne r0, psp\n\t"
                     "b board_hardfault_record\n");
}

void Default_Handler(void)
{
    board_unexpected_irq();
}

__attribute__((noreturn)) void Reset_Handler(void)
{
    /* The FPU first: any float instruction before this would fault. */
    TSE_CPACR |= CPACR_CP10_CP11_FULL;
    /* Our own vector table, wherever the board links the image (board_desc.h: behind a
     * bootloader it is not at 0x08000000, and not every bootloader sets VTOR before it jumps). */
    TSE_SCB->VTOR = (uint32_t)(uintptr_t)vectors;
    __asm__ volatile("dsb\n\tisb" ::: "memory");
    copy_words(&_sdata, &_sidata, &_edata);
    zero_words(&_sbss, &_ebss);
    /* Divide by zero traps instead of returning 0; the configurable faults get their own
     * handlers (aliased to the HardFault record). */
    TSE_SCB->CCR |= SCB_CCR_DIV_0_TRP;
    TSE_SCB->SHCSR |= SCB_SHCSR_MEMFAULTENA | SCB_SHCSR_BUSFAULTENA | SCB_SHCSR_USGFAULTENA;
    main();
    for (;;)
        __asm__ volatile("wfi");
}
