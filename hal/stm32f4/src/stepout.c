/* STEP, DIR and ENABLE outputs.  A STEP pulse rises in the step interrupt and falls when TIM4,
 * started as a one-shot of step_pulse_ns, runs out: the width is the drivers' parameter,
 * whatever the step rate, and no interrupt time is spent waiting. */
#include "hal_stm32f4/board_io.h"
#include "hal_stm32f4/fault.h"
#include "hal_stm32f4/pinmap.h"
#include "hal_stm32f4/regs_core.h"
#include "hal_stm32f4/regs_tim.h"

#define PRIO_PULSE 1u

static struct {
    uint32_t timer_hz;
    uint32_t pulse_ticks;
} out;

/* ENABLE's active level: the board's until board_stepper_hal is told otherwise (the enable_level
 * parameter), so that board_outputs_safe, which may run before it, never drives the drivers on. */
static bool enable_high = ENABLE_ACTIVE_HIGH != 0;

bool board_enable_active_high(void)
{
    return enable_high;
}

static void set_dir(void *ctx, uint8_t forward)
{
    (void)ctx;
    const uint32_t f = forward & STEP_MASK_ALL;
    PIN_DIR_PORT->BSRR = f << PIN_DIR_SHIFT | (~f & STEP_MASK_ALL) << (PIN_DIR_SHIFT + 16u);
}

static void pulse(void *ctx, uint8_t mask)
{
    (void)ctx;
    PIN_STEP_PORT->BSRR = (uint32_t)(mask & STEP_MASK_ALL) << PIN_STEP_SHIFT;
    /* (Re)start the one-shot: a pulse of another axis still high is lengthened, never cut. */
    TSE_TIM4->CNT = 0;
    TSE_TIM4->CR1 = TIM_CR1_OPM | TIM_CR1_URS | TIM_CR1_CEN;
}

void TIM4_IRQHandler(void);
void TIM4_IRQHandler(void)
{
    TSE_TIM4->SR = 0;
    TSE_TIM4->CR1 = TIM_CR1_OPM | TIM_CR1_URS; /* stopped, should the one-pulse mode not be */
    PIN_STEP_PORT->BSRR = STEP_MASK_ALL << (PIN_STEP_SHIFT + 16u);
}

static void enable(void *ctx, bool on)
{
    (void)ctx;
    const uint32_t bit = 1u << PIN_ENABLE;
    PIN_ENABLE_PORT->BSRR = (on == enable_high) ? bit : bit << 16;
}

static void timing(void *ctx, uint32_t pulse_ns, uint32_t dir_setup_ns)
{
    (void)ctx;
    (void)dir_setup_ns; /* the step generator keeps it, in step interrupts */
    /* Rounded up: a pulse is never shorter than asked. */
    uint64_t ticks = ((uint64_t)pulse_ns * out.timer_hz + 999999999u) / 1000000000u;
    if (ticks < 2u)
        ticks = 2u;
    if (ticks > 0xFFFFu)
        ticks = 0xFFFFu;
    out.pulse_ticks = (uint32_t)ticks;
    TSE_TIM4->ARR = out.pulse_ticks;
}

hal_stepper board_stepper_hal(uint32_t timer_hz, int enable_active_high)
{
    enable_high = enable_active_high < 0 ? ENABLE_ACTIVE_HIGH != 0 : enable_active_high != 0;
    enable(0, false);
    out.timer_hz = timer_hz;
    TSE_TIM4->CR1 = 0;
    TSE_TIM4->PSC = 0;
    TSE_TIM4->EGR = TIM_EGR_UG; /* loads PSC */
    TSE_TIM4->SR = 0;
    TSE_TIM4->DIER = TIM_DIER_UIE;
    timing(0, 2500u, 0u); /* the DM542's 2.5 us until the controller programs step_pulse_ns */
    tse_nvic_enable(IRQ_TIM4, PRIO_PULSE);
    const hal_stepper h = {0, set_dir, pulse, enable, timing};
    return h;
}

void board_outputs_safe(void)
{
    TSE_TIM2->CR1 = 0; /* no further step interrupt */
    TSE_TIM2->DIER = 0;
    enable(0, false);
    PIN_STEP_PORT->BSRR = STEP_MASK_ALL << (PIN_STEP_SHIFT + 16u);
}
