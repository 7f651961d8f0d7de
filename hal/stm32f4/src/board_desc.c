/* The board description (board_desc.h) as the table the drivers read.  Compiled once per board
 * with TSE_BOARD_HEADER naming its file (CMake: tse_board_desc_NAME); BOARD_DESC_SYMBOL renames
 * the table where one host program holds several (tests/boards). */
#include "hal_stm32f4/board_desc.h"

#include TSE_BOARD_HEADER

#ifndef BOARD_DESC_SYMBOL
#define BOARD_DESC_SYMBOL tse_board_desc
#endif

/* The PLL from the crystal unless the description gives it: a VCO input of 2 MHz (the least
 * jitter, datasheet) from a crystal of whole 2 MHz, else 1 MHz; VCO 336 MHz, SYSCLK = VCO / 2 =
 * 168 MHz, USB = VCO / 7 = 48 MHz. */
#ifndef BOARD_PLL_M
#define BOARD_VCO_IN_HZ (BOARD_HSE_HZ % 2000000u == 0 ? 2000000u : 1000000u)
#define BOARD_PLL_M (BOARD_HSE_HZ / BOARD_VCO_IN_HZ)
#define BOARD_PLL_N (336000000u / BOARD_VCO_IN_HZ)
#define BOARD_PLL_P 2u
#define BOARD_PLL_Q 7u
#endif

#ifndef BOARD_ENABLE2
#define BOARD_ENABLE2 BOARD_PIN_NONE
#endif
#ifndef BOARD_ENABLE3
#define BOARD_ENABLE3 BOARD_PIN_NONE
#endif
#ifndef BOARD_ENABLE4
#define BOARD_ENABLE4 BOARD_PIN_NONE
#endif
#ifndef BOARD_ENABLE5
#define BOARD_ENABLE5 BOARD_PIN_NONE
#endif
#ifndef BOARD_ENABLE6
#define BOARD_ENABLE6 BOARD_PIN_NONE
#endif
#ifndef BOARD_PLANTED_EXPECT
#define BOARD_PLANTED_EXPECT 0
#endif

/* The six of each, for the table and the identity alike. */
#define STEP_PINS {BOARD_STEP1, BOARD_STEP2, BOARD_STEP3, BOARD_STEP4, BOARD_STEP5, BOARD_STEP6}
#define DIR_PINS {BOARD_DIR1, BOARD_DIR2, BOARD_DIR3, BOARD_DIR4, BOARD_DIR5, BOARD_DIR6}
#define LIM_PINS {BOARD_LIM1, BOARD_LIM2, BOARD_LIM3, BOARD_LIM4, BOARD_LIM5, BOARD_LIM6}
#define ENABLE_PINS {BOARD_ENABLE1, BOARD_ENABLE2, BOARD_ENABLE3, BOARD_ENABLE4, BOARD_ENABLE5, BOARD_ENABLE6}

const board_desc BOARD_DESC_SYMBOL = {
    .name = BOARD_NAME,
    .sources = BOARD_SOURCES,
    .part = BOARD_PART,
    .package = BOARD_PACKAGE,
    .flash_kib = BOARD_FLASH_KIB,
    .hse_hz = BOARD_HSE_HZ,
    .pll_m = BOARD_PLL_M,
    .pll_n = BOARD_PLL_N,
    .pll_p = BOARD_PLL_P,
    .pll_q = BOARD_PLL_Q,
    .app_addr = BOARD_APP_ADDR,
    .param_sector = BOARD_PARAM_SECTOR,
    .step = STEP_PINS,
    .dir = DIR_PINS,
    .lim = LIM_PINS,
    .limh = {BOARD_LIMH1, BOARD_LIMH2, BOARD_LIMH3, BOARD_LIMH4, BOARD_LIMH5, BOARD_LIMH6},
    .enable = ENABLE_PINS,
    .enable_active_high = BOARD_ENABLE_ACTIVE_HIGH,
    .limh_fitted = BOARD_LIMH_FITTED,
    .estop = BOARD_ESTOP,
    .led = BOARD_LED,
    .led_active_high = BOARD_LED_ACTIVE_HIGH,
    .can_rx = BOARD_CAN_RX,
    .can_tx = BOARD_CAN_TX,
    .can_af = BOARD_CAN_AF,
    .boot_usart = BOARD_BOOT_USART,
    .boot_tx = BOARD_BOOT_TX,
    .boot_tx_af = BOARD_BOOT_TX_AF,
    .planted_expect = BOARD_PLANTED_EXPECT,
};

#ifdef TSE_BOARD_IMAGE
/* The image's identity, where a tool finds it without symbols (objcopy -j .tse_board): the
 * emulator's harness reads it to wire the rig to this board's pins (docs/emulator.md). */
__attribute__((section(".tse_board"), used)) const board_identity tse_board_identity = {
    .id = "tse-board:" BOARD_NAME,
    .hse_hz = BOARD_HSE_HZ,
    .app_addr = BOARD_APP_ADDR,
    .step = STEP_PINS,
    .dir = DIR_PINS,
    .lim = LIM_PINS,
    .enable = ENABLE_PINS,
    .enable_active_high = BOARD_ENABLE_ACTIVE_HIGH,
    .estop = BOARD_ESTOP,
    .led = BOARD_LED,
    .led_active_high = BOARD_LED_ACTIVE_HIGH,
    .can_rx = BOARD_CAN_RX,
    .can_tx = BOARD_CAN_TX,
    .boot_usart = BOARD_BOOT_USART,
    .boot_tx = BOARD_BOOT_TX,
};
_Static_assert(sizeof(board_identity) == 48 + 8 + 4 * BOARD_SLIDES + 8, "board_identity: no padding");
#endif
