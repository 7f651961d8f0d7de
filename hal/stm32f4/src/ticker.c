/* The board's hal_ticker: TIM2's update interrupt is the step interrupt, TIM3's only counts
 * control ticks, and start() runs the main loop that makes the control calls. */
#include "hal_stm32f4/board_io.h"
#include "hal_stm32f4/pinmap.h"
#include "hal_stm32f4/regs_core.h"
#include "hal_stm32f4/regs_tim.h"

static struct {
    void (*step)(void *arg);
    void *arg;
    board_ticker *t;
} isr;

void TIM2_IRQHandler(void);
void TIM2_IRQHandler(void)
{
    TSE_TIM2->SR = 0;
    isr.step(isr.arg);
    ++isr.t->steps;
}

void TIM3_IRQHandler(void);
void TIM3_IRQHandler(void)
{
    TSE_TIM3->SR = 0;
    ++isr.t->due;
}

static void periodic(tse_tim_regs *tim, uint32_t psc, uint32_t arr)
{
    tim->CR1 = 0;
    tim->PSC = psc;
    tim->ARR = arr;
    tim->CNT = 0;
    tim->EGR = TIM_EGR_UG;
    tim->SR = 0;
    tim->DIER = TIM_DIER_UIE;
    tim->CR1 = TIM_CR1_URS | TIM_CR1_CEN;
}

static int start(void *ctx, uint32_t control_hz, void (*control)(void *arg), uint32_t step_hz,
                 void (*step)(void *arg), void *arg)
{
    board_ticker *t = ctx;
    /* Both rates exact in timer counts, or refused: the firmware's time is their ratio. */
    if (step_hz == 0 || control_hz == 0 || t->timer_hz % step_hz != 0 || t->timer_hz % 1000000u != 0 ||
        1000000u % control_hz != 0)
        return -1;
    isr.step = step;
    isr.arg = arg;
    isr.t = t;
    t->stop = 0;
    t->done = t->due;
    periodic(TSE_TIM3, t->timer_hz / 1000000u - 1u, 1000000u / control_hz - 1u);
    periodic(TSE_TIM2, 0u, t->timer_hz / step_hz - 1u);
    tse_nvic_enable(IRQ_TIM3, PRIO_CONTROL);
    tse_nvic_enable(IRQ_TIM2, PRIO_STEP);
    while (!t->stop) {
        const uint32_t due = t->due;
        if (due == t->done) {
            __asm__ volatile("wfi");
            continue;
        }
        t->late += due - t->done - 1u;
        t->done = due;
        control(arg);
        if (t->idle)
            t->idle();
    }
    return 0;
}

void board_ticker_halt(void)
{
    tse_nvic_disable(IRQ_TIM2);
    tse_nvic_disable(IRQ_TIM3);
    TSE_TIM2->CR1 = 0;
    TSE_TIM3->CR1 = 0;
}

static void stop(void *ctx)
{
    board_ticker *t = ctx;
    t->stop = 1;
}

hal_ticker board_ticker_hal(board_ticker *t)
{
    const hal_ticker h = {t, start, stop};
    return h;
}
