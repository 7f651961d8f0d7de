/*
 * The TSE controller's STM32F407 machine: the type names of our device models and the
 * connections (GPIO lines, clocks) between them that the SoC (tse_f407_soc.c) wires up.
 * Register behaviour is written from the STM32F405/407 reference manual (RM0090); each model's
 * file says what it models and what it does not.
 *
 * SPDX-License-Identifier: GPL-2.0-or-later
 */
#ifndef TSE_F407_H
#define TSE_F407_H

#define TYPE_TSE_F407_SOC "tse-f407-soc"
#define TYPE_STM32F4_RCC "stm32f4-rcc"
#define TYPE_STM32F4_PWR "stm32f4-pwr"
#define TYPE_STM32F4_FLASH "stm32f4-flash"
#define TYPE_STM32F4_GPIO "stm32f4-gpio"
#define TYPE_STM32F4_EXTI "stm32f4-exti"
#define TYPE_STM32F4_SYSCFG "stm32f4-syscfg"
#define TYPE_STM32F4_TIM "stm32f4-tim"
#define TYPE_STM32F4_IWDG "stm32f4-iwdg"
#define TYPE_STM32F4_BXCAN "stm32f4-bxcan"
#define TYPE_TSE_RIG "tse-rig"
#define TYPE_CAN_HOST_CHARDEV "can-host-chardev"

/* ---- RCC (stm32f4_rcc.c) ---- */
/* Clock outputs, recomputed from PLLCFGR/CFGR whenever they change. */
#define RCC_CLK_HCLK "hclk"        /* AHB, core */
#define RCC_CLK_PCLK1 "pclk1"      /* APB1 peripherals (bxCAN) */
#define RCC_CLK_PCLK2 "pclk2"      /* APB2 peripherals (USART1) */
#define RCC_CLK_TIMCLK1 "timclk1"  /* APB1 timers: PCLK1, twice it when APB1 is divided */
#define RCC_CLK_TIMCLK2 "timclk2"  /* APB2 timers (TIM11): PCLK2, twice it when APB2 is divided */
#define RCC_CLK_HSE_RTC "hse-rtc"  /* HSE / RTCPRE while HSE is ready and RTCPRE >= 2, else off */
/* Enable lines, one per bit of AHB1ENR, APB1ENR and APB2ENR (level = the bit). */
#define RCC_GPIO_AHB1EN "ahb1en"
#define RCC_GPIO_APB1EN "apb1en"
#define RCC_GPIO_APB2EN "apb2en"
/* Reset requests, a pulse each: the reset that follows sets the matching RCC_CSR flags. */
#define RCC_GPIO_RESET "reset-request"
enum { RCC_RESET_SOFTWARE, RCC_RESET_IWDG, RCC_RESET_POWER_ON, RCC_RESET_PIN, RCC_RESET_N };

/* ---- GPIO (stm32f4_gpio.c) ---- */
#define GPIO_IN_EXT "ext"   /* 16 lines: what drives each pin from outside (level 0/1; -1 floating) */
#define GPIO_OUT_PIN "pin"  /* 16 lines: each pin's level, on every change (to the board) */
#define GPIO_OUT_EXTI "exti" /* 16 lines: the same levels (to SYSCFG's EXTI multiplexer) */
#define GPIO_OUT_AF "af"    /* 16 lines: the pin's alternate function while in AF mode, else -1 */

/* ---- EXTI (stm32f4_exti.c) ---- */
#define EXTI_IN_LINE "line" /* 23 inputs; outputs (sysbus IRQs) listed in the file */
#define EXTI_NUM_LINES 23
#define EXTI_NUM_IRQS 14

/* ---- CAN (stm32f4_bxcan.c, can_host_chardev.c) ---- */
/* A frame's nominal length on the bus in bits, intermission included, without stuff bits:
 * 44 + 8 x len bits standard, 64 + 8 x len extended, plus 3 (ISO 11898-1). */
static inline uint32_t tse_can_frame_bits(bool extended, bool rtr, unsigned len)
{
    return (extended ? 64u : 44u) + 8u * (rtr ? 0u : (len > 8u ? 8u : len)) + 3u;
}

/* ---- bxCAN (stm32f4_bxcan.c) ---- */
#define BXCAN_IN_RX_AF "rx-af" /* the CAN RX pin's alternate function (from GPIO "af") */
#define BXCAN_IN_TX_AF "tx-af"
#define BXCAN_IN_BUS_ERROR "bus-error" /* level 1: the bus is held in error (the rig's canerr) */
/* A frame taken into a receive FIFO, for an observer (the rig): pulsed to 1 + the frame's
 * identifier (standard or extended), then back to 0. */
#define BXCAN_OUT_RX "rx"

/* ---- FLASH (stm32f4_flash.c) ---- */
#define FLASH_OUT_OP "op" /* pulsed as an erase or a program operation starts, for an observer (the rig) */

/* ---- IWDG (stm32f4_iwdg.c) ---- */
#define IWDG_OUT_RESET "reset" /* pulsed when the counter reaches 0 */
#define IWDG_OUT_RELOAD "reload" /* pulsed at every reload (KR = 0xAAAA), for an observer (the rig) */

/* ---- rig (tse_rig.c) ---- */
#define RIG_IN_STEP "step"     /* 6 lines */
#define RIG_IN_DIR "dir"       /* 6 lines */
#define RIG_IN_ENABLE "enable" /* 1 line */
#define RIG_OUT_SWITCH "switch" /* 6 lines: the low homing switches' pins (1 = open = pressed) */
#define RIG_OUT_ESTOP "estop"   /* 1 line: the e-stop pin (1 = chain open) */
#define RIG_OUT_POWER "power-cycle" /* pulsed by the `reset` request */
#define RIG_OUT_CANERR "canerr"     /* level: `canerr on|off` */
#define RIG_IN_CAN_RX "can-rx"      /* 1 line: bxCAN's BXCAN_OUT_RX (`firststep`) */
#define RIG_IN_FEED "feed"          /* 1 line: the IWDG's reloads (`feedgap`) */
#define RIG_IN_FLASH_OP "flash-op"  /* 1 line: the flash's FLASH_OUT_OP (`flashops`, `cutflash`) */

/* ---- SoC (tse_f407_soc.c) ---- */
#define SOC_IN_POWER "power-cycle" /* a pulse: RAM lost, power-on reset */

#endif
