/* The clock tree of hal_stm32f4/clock.h. */
#include "hal_stm32f4/clock.h"

#include "hal_stm32f4/board_desc.h"
#include "hal_stm32f4/regs_flash.h"
#include "hal_stm32f4/regs_rcc.h"

#define HSI_HZ 16000000u
/* The crystal starts within 2 ms, the PLL locks within 0.2 ms (datasheet); at 16 MHz one poll
 * of this loop takes a few cycles, so 100,000 polls are tens of milliseconds: ample on a
 * healthy board, and a prompt answer on a dead one. */
#define WAIT_POLLS 100000u

/* The crystal and the PLL are the board description's (board_desc.h, src/board_desc.c): VCO in
 * = crystal / M = 2 MHz where the crystal allows (datasheet: 1..2 MHz, 2 MHz for the least
 * jitter), else 1 MHz; VCO out = 336 MHz, SYSCLK = VCO / P = 168 MHz, USB/SDIO = VCO / Q =
 * 48 MHz.  The host checker (tests/boards) holds every description to those. */

/* Flash wait states at 168 MHz and 2.7..3.6 V (RM0090 table 10): 5. */
#define FLASH_LATENCY 5u

/* The AHB1ENR bits of the ports the description uses (bit n: port n). */
static uint32_t board_gpio_ports(void)
{
    const board_desc *d = &tse_board_desc;
    const uint8_t *const groups[] = {d->step, d->dir, d->lim, d->limh, d->enable};
    uint32_t m = 1u << BOARD_PIN_PORT(d->estop) | 1u << BOARD_PIN_PORT(d->can_rx) |
                 1u << BOARD_PIN_PORT(d->can_tx);
    if (d->led != BOARD_PIN_NONE)
        m |= 1u << BOARD_PIN_PORT(d->led);
    for (unsigned g = 0; g < sizeof groups / sizeof groups[0]; ++g)
        for (unsigned k = 0; k < BOARD_SLIDES; ++k)
            if (groups[g][k] != BOARD_PIN_NONE)
                m |= 1u << BOARD_PIN_PORT(groups[g][k]);
    return m;
}

static int wait_set(volatile uint32_t *reg, uint32_t mask, uint32_t value)
{
    for (uint32_t i = 0; i < WAIT_POLLS; ++i)
        if ((*reg & mask) == value)
            return 0;
    return -1;
}

void board_clock_enable_peripherals(void)
{
    TSE_RCC->AHB1ENR |= board_gpio_ports();
    TSE_RCC->APB1ENR |= RCC_APB1ENR_TIM2 | RCC_APB1ENR_TIM3 | RCC_APB1ENR_TIM4 | RCC_APB1ENR_TIM5 |
                        RCC_APB1ENR_CAN1 | RCC_APB1ENR_PWR;
    TSE_RCC->APB2ENR |= RCC_APB2ENR_SYSCFG;
    (void)TSE_RCC->APB2ENR; /* the enable takes two bus cycles to reach the peripherals */
}

static board_clocks reset_clocks(const char *failed)
{
    /* Back to the internal oscillator with no prescalers, whatever was half done. */
    TSE_RCC->CFGR &= ~RCC_CFGR_SW_MASK;
    TSE_RCC->CR &= ~RCC_CR_PLLON;
    const board_clocks c = {HSI_HZ, HSI_HZ, HSI_HZ, HSI_HZ, failed, {HSE_CHECK_NOT_RUN, 0, tse_board_desc.hse_hz, 0}};
    TSE_RCC->CFGR &= ~((0x7u << 10) | (0x7u << 13));
    return c;
}

board_clocks board_clock_init(void)
{
    TSE_RCC->APB1ENR |= RCC_APB1ENR_PWR;
    TSE_PWR_CR |= PWR_CR_VOS;

    TSE_RCC->CR |= RCC_CR_HSEON;
    if (wait_set(&TSE_RCC->CR, RCC_CR_HSERDY, RCC_CR_HSERDY) != 0)
        return reset_clocks("HSERDY");
    /* The crystal the PLL is set for, measured against the HSI while it is still the clock. */
    const hse_check crystal = board_hse_check(tse_board_desc.hse_hz);
    if (crystal.verdict != HSE_CHECK_OK) {
        board_clocks off = reset_clocks("crystal");
        off.crystal = crystal;
        return off;
    }

    TSE_RCC->CR &= ~RCC_CR_PLLON;
    const board_desc *d = &tse_board_desc;
    TSE_RCC->PLLCFGR = RCC_PLLCFGR(d->pll_m, d->pll_n, d->pll_p, d->pll_q) | RCC_PLLCFGR_SRC_HSE;
    TSE_RCC->CR |= RCC_CR_PLLON;
    if (wait_set(&TSE_RCC->CR, RCC_CR_PLLRDY, RCC_CR_PLLRDY) != 0)
        return reset_clocks("PLLRDY");

    /* Wait states before the clock rises; the ART caches are reset while off, then enabled. */
    TSE_FLASH->ACR = FLASH_ACR_ICRST | FLASH_ACR_DCRST;
    TSE_FLASH->ACR = FLASH_LATENCY | FLASH_ACR_PRFTEN | FLASH_ACR_ICEN | FLASH_ACR_DCEN;
    if ((TSE_FLASH->ACR & FLASH_ACR_LATENCY_MASK) != FLASH_LATENCY)
        return reset_clocks("FLASH_LATENCY");

    TSE_RCC->CFGR = (TSE_RCC->CFGR & ~((0xFu << 4) | (0x7u << 10) | (0x7u << 13))) | RCC_CFGR_PPRE1_DIV4 |
                    RCC_CFGR_PPRE2_DIV2;
    TSE_RCC->CFGR = (TSE_RCC->CFGR & ~RCC_CFGR_SW_MASK) | RCC_CFGR_SW_PLL;
    if (wait_set(&TSE_RCC->CFGR, RCC_CFGR_SWS_MASK, RCC_CFGR_SWS_PLL) != 0)
        return reset_clocks("SWS");

    const uint32_t sysclk = d->hse_hz / d->pll_m * d->pll_n / d->pll_p;
    const board_clocks c = {sysclk, sysclk / 4u, sysclk / 2u, sysclk / 2u, 0, crystal};
    return c;
}
