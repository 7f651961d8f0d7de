/* Independent watchdog (hal_stm32f4/iwdg.h). */
#include "hal_stm32f4/iwdg.h"

#include "hal_stm32f4/regs_misc.h"
#include "hal_stm32f4/regs_rcc.h"

#define LSI_HZ 32000u
#define PRESCALER_CODE 4u /* /64: 0.5 kHz counts, up to 8.2 s */
#define DIVIDER 64u
#define WAIT_POLLS 100000u

int board_iwdg_start(uint32_t timeout_ms)
{
    uint32_t reload = timeout_ms * (LSI_HZ / DIVIDER) / 1000u;
    if (reload < 1u)
        reload = 1u;
    if (reload > 0xFFFu)
        reload = 0xFFFu;
    TSE_DBGMCU_APB1_FZ |= DBGMCU_IWDG_STOP; /* a debugger's halt is not a hang */
    TSE_IWDG->KR = IWDG_KEY_START;
    TSE_IWDG->KR = IWDG_KEY_UNLOCK;
    TSE_IWDG->PR = PRESCALER_CODE;
    TSE_IWDG->RLR = reload;
    int rc = -1;
    for (uint32_t i = 0; i < WAIT_POLLS; ++i)
        if ((TSE_IWDG->SR & (IWDG_SR_PVU | IWDG_SR_RVU)) == 0) {
            rc = 0;
            break;
        }
    TSE_IWDG->KR = IWDG_KEY_RELOAD;
    return rc;
}

void board_iwdg_feed(void)
{
    TSE_IWDG->KR = IWDG_KEY_RELOAD;
}

int board_reset_was_watchdog(void)
{
    const int wd = (TSE_RCC->CSR & RCC_CSR_IWDGRSTF) != 0;
    TSE_RCC->CSR |= RCC_CSR_RMVF;
    return wd;
}
