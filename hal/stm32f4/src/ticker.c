/* The board's two controller interrupts: TIM2's update interrupt is the step interrupt, TIM3's the
 * control tick (board_io.h). */
#include "hal_stm32f4/board_io.h"
#include "hal_stm32f4/pinmap.h"
#include "hal_stm32f4/regs_core.h"
#include "hal_stm32f4/regs_tim.h"

static board_ticker *ticker;

void TIM2_IRQHandler(void);
void TIM2_IRQHandler(void)
{
    TSE_TIM2->SR = 0;
    board_step();
    ++ticker->steps;
}

void TIM3_IRQHandler(void);
void TIM3_IRQHandler(void)
{
    const uint32_t late = TSE_TIM3->CNT; /* microseconds since the period began */
    if (late > ticker->control_delay_max_us)
        ticker->control_delay_max_us = late;
    TSE_TIM3->SR = 0;
    board_control();
    ++ticker->controls;
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

int board_ticker_start(board_ticker *t, uint32_t control_hz, uint32_t step_hz)
{
    /* Both rates exact in timer counts, or refused: the firmware's time is their ratio. */
    if (step_hz == 0 || control_hz == 0 || t->timer_hz % step_hz != 0 || t->timer_hz % 1000000u != 0 ||
        1000000u % control_hz != 0)
        return -1;
    ticker = t;
    periodic(TSE_TIM3, t->timer_hz / 1000000u - 1u, 1000000u / control_hz - 1u);
    periodic(TSE_TIM2, 0u, t->timer_hz / step_hz - 1u);
    tse_nvic_enable(IRQ_TIM3, PRIO_CONTROL);
    tse_nvic_enable(IRQ_TIM2, PRIO_STEP);
    return 0;
}

void board_ticker_halt(void)
{
    tse_nvic_disable(IRQ_TIM2);
    tse_nvic_disable(IRQ_TIM3);
    TSE_TIM2->CR1 = 0;
    TSE_TIM3->CR1 = 0;
}
