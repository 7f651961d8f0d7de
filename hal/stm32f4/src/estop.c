/* The e-stop input as an interrupt: the EXTI line of the description's pin (its number), on the
 * rising edge (the NC chain opened).  Lines 0..4 have an interrupt each, 5..9 and 10..15 share
 * one (RM0090 table 61): every handler below takes only the e-stop's line. */
#include "hal_stm32f4/board_io.h"
#include "hal_stm32f4/pinmap.h"
#include "hal_stm32f4/regs_core.h"
#include "hal_stm32f4/regs_misc.h"

static struct {
    void (*fn)(void *arg);
    void *arg;
} on;

static void take(void)
{
    const uint32_t line = 1u << BOARD_PIN_NUM(tse_board_desc.estop);
    if ((TSE_EXTI->PR & line) && on.fn) {
        TSE_EXTI->PR = line;
        on.fn(on.arg);
    }
}

void EXTI0_IRQHandler(void);
void EXTI1_IRQHandler(void);
void EXTI2_IRQHandler(void);
void EXTI3_IRQHandler(void);
void EXTI4_IRQHandler(void);
void EXTI9_5_IRQHandler(void);
void EXTI15_10_IRQHandler(void);
void EXTI0_IRQHandler(void)
{
    take();
}
void EXTI1_IRQHandler(void)
{
    take();
}
void EXTI2_IRQHandler(void)
{
    take();
}
void EXTI3_IRQHandler(void)
{
    take();
}
void EXTI4_IRQHandler(void)
{
    take();
}
void EXTI9_5_IRQHandler(void)
{
    take();
}
void EXTI15_10_IRQHandler(void)
{
    take();
}

static unsigned irq_of_line(unsigned line)
{
    if (line <= 4u)
        return IRQ_EXTI0 + line;
    return line <= 9u ? IRQ_EXTI9_5 : IRQ_EXTI15_10;
}

void board_estop_irq_init(void (*on_estop)(void *arg), void *arg)
{
    on.fn = on_estop;
    on.arg = arg;
    const uint8_t p = tse_board_desc.estop;
    const unsigned n = BOARD_PIN_NUM(p);
    /* SYSCFG_EXTICR: 4 bits a line, the port's index (A = 0). */
    const unsigned reg = n / 4u, shift = 4u * (n % 4u);
    TSE_SYSCFG->EXTICR[reg] = (TSE_SYSCFG->EXTICR[reg] & ~(0xFu << shift)) | BOARD_PIN_PORT(p) << shift;
    const uint32_t line = 1u << n;
    TSE_EXTI->FTSR &= ~line;
    TSE_EXTI->RTSR |= line;
    TSE_EXTI->PR = line;
    TSE_EXTI->IMR |= line;
    tse_nvic_enable(irq_of_line(n), PRIO_ESTOP);
}
