/* The microsecond clock: TIM5 free-running at 1 MHz, its 32 bits extended in software. */
#include "hal_stm32f4/board_io.h"
#include "hal_stm32f4/pinmap.h"
#include "hal_stm32f4/regs_core.h"
#include "hal_stm32f4/regs_tim.h"

static struct {
    uint32_t last;
    uint64_t high;
} tb;

static uint64_t now_us(void *ctx)
{
    (void)ctx;
    /* The main loop and the control interrupt both extend the counter: the control level and
     * below are masked for these few instructions (the step and e-stop interrupts never call it). */
    const uint32_t saved = tse_basepri_raise(PRIO_CONTROL);
    const uint32_t c = TSE_TIM5->CNT;
    if (c < tb.last)
        tb.high += 1ull << 32;
    tb.last = c;
    const uint64_t t = tb.high | c;
    tse_basepri_restore(saved);
    return t;
}

hal_clock board_clock_hal(uint32_t timer_hz)
{
    TSE_TIM5->CR1 = 0;
    TSE_TIM5->PSC = timer_hz / 1000000u - 1u;
    TSE_TIM5->ARR = 0xFFFFFFFFu;
    TSE_TIM5->CNT = 0;
    TSE_TIM5->EGR = TIM_EGR_UG;
    TSE_TIM5->SR = 0;
    TSE_TIM5->CR1 = TIM_CR1_CEN;
    tb.last = 0;
    tb.high = 0;
    const hal_clock h = {0, now_us};
    return h;
}
