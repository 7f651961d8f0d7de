/* The e-stop input as an interrupt: EXTI line 8 on the rising edge of PA8 (the NC chain opened). */
#include "hal_stm32f4/board_io.h"
#include "hal_stm32f4/pinmap.h"
#include "hal_stm32f4/regs_core.h"
#include "hal_stm32f4/regs_misc.h"

static struct {
    void (*fn)(void *arg);
    void *arg;
} on;

void EXTI9_5_IRQHandler(void);
void EXTI9_5_IRQHandler(void)
{
    const uint32_t line = 1u << PIN_ESTOP;
    if (TSE_EXTI->PR & line) {
        TSE_EXTI->PR = line;
        on.fn(on.arg);
    }
}

void board_estop_irq_init(void (*on_estop)(void *arg), void *arg)
{
    on.fn = on_estop;
    on.arg = arg;
    const unsigned reg = PIN_ESTOP / 4u, shift = 4u * (PIN_ESTOP % 4u);
    TSE_SYSCFG->EXTICR[reg] = (TSE_SYSCFG->EXTICR[reg] & ~(0xFu << shift)) | PIN_ESTOP_EXTI_PORT << shift;
    const uint32_t line = 1u << PIN_ESTOP;
    TSE_EXTI->FTSR &= ~line;
    TSE_EXTI->RTSR |= line;
    TSE_EXTI->PR = line;
    TSE_EXTI->IMR |= line;
    tse_nvic_enable(IRQ_EXTI9_5, PRIO_ESTOP);
}
