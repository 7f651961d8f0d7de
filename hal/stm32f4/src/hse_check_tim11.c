/* The crystal measured with TIM11 (hal_stm32f4/hse_check.h): TIM11 counts the HSI and captures
 * HSE_RTC on channel 1.  Its registers (RM0090 section 19, TIM10/11/13/14) are at TIM2..TIM5's
 * offsets (CR1, SR, EGR, CCMR1, CCER, CNT, PSC, ARR, CCR1), plus TIM11_OR at 0x50. */
#include "hal_stm32f4/hse_check.h"

#include "hal_stm32f4/regs_rcc.h"
#include "hal_stm32f4/regs_tim.h"

#define HSI_HZ 16000000u

#define TSE_TIM11 ((tse_tim_regs *)0x40014800u)
#define TSE_TIM11_OR (*(volatile uint32_t *)0x40014850u)
#define TIM11_OR_TI1_RMP_HSE_RTC 0x2u   /* RM0090 section 19, TIM11_OR */
#define RCC_APB2ENR_TIM11 (1u << 18)    /* RM0090 7.3.14 */
#define RCC_CFGR_RTCPRE_SHIFT 16u       /* RM0090 7.3.3: HSE / RTCPRE, 2..31 */
#define RCC_CFGR_RTCPRE_MASK (0x1Fu << RCC_CFGR_RTCPRE_SHIFT)
/* CCMR1 (input capture mode, RM0090 section 19): CC1S = 01 (IC1 on TI1), IC1PSC = 11 (every 8 events),
 * IC1F = 0 (no filter); CCER: CC1E, rising edges (CC1P = CC1NP = 0); SR: CC1IF, CC1OF. */
#define TIM_CCMR1_CC1S_TI1 0x1u
#define TIM_CCMR1_IC1PSC_8 (0x3u << 2)
#define TIM_CCER_CC1E (1u << 0)
#define TIM_SR_CC1OF (1u << 9)

_Static_assert(HSE_CHECK_IC_PSC == 8u, "IC1PSC is set for 8 events a capture");

static hse_poll tim11_poll(void *ctx, uint16_t *value)
{
    (void)ctx;
    const uint32_t sr = TSE_TIM11->SR;
    if (!(sr & TIM_SR_CC1IF)) {
        *value = (uint16_t)TSE_TIM11->CNT;
        return HSE_POLL_NONE;
    }
    *value = (uint16_t)TSE_TIM11->CCR1; /* the read clears CC1IF */
    if (sr & TIM_SR_CC1OF) {
        TSE_TIM11->SR = ~TIM_SR_CC1OF; /* rc_w0 */
        return HSE_POLL_MISSED;
    }
    return HSE_POLL_CAPTURE;
}

hse_check board_hse_check(uint32_t expected_hz)
{
    const uint32_t rtcpre = TSE_RCC->CFGR & RCC_CFGR_RTCPRE_MASK;
    TSE_RCC->CFGR = (TSE_RCC->CFGR & ~RCC_CFGR_RTCPRE_MASK) | HSE_CHECK_RTCPRE << RCC_CFGR_RTCPRE_SHIFT;
    TSE_RCC->APB2ENR |= RCC_APB2ENR_TIM11;
    (void)TSE_RCC->APB2ENR; /* the enable takes two bus cycles to reach the peripheral */

    TSE_TIM11->CR1 = 0;
    TSE_TIM11->PSC = 0;
    TSE_TIM11->ARR = 0xFFFFu;
    TSE_TIM11->EGR = TIM_EGR_UG; /* loads PSC */
    TSE_TIM11_OR = TIM11_OR_TI1_RMP_HSE_RTC;
    TSE_TIM11->CCMR1 = TIM_CCMR1_CC1S_TI1 | TIM_CCMR1_IC1PSC_8;
    TSE_TIM11->CCER = TIM_CCER_CC1E;
    TSE_TIM11->SR = 0;
    TSE_TIM11->CR1 = TIM_CR1_CEN;

    const hse_check_timer timer = {tim11_poll, 0};
    const hse_check c = hse_check_measure(&timer, HSI_HZ, expected_hz);

    TSE_TIM11->CR1 = 0;
    TSE_TIM11->CCER = 0;
    TSE_TIM11_OR = 0;
    TSE_RCC->APB2ENR &= ~RCC_APB2ENR_TIM11;
    TSE_RCC->CFGR = (TSE_RCC->CFGR & ~RCC_CFGR_RTCPRE_MASK) | rtcpre;
    return c;
}
