/* A board, described by data: which part, which crystal, which pin carries which signal, at
 * which level, where the image and the parameter log live.  One small file a board,
 * hal/stm32f4/boards/NAME.h, written in the vocabulary below (BOARD_PIN(C, 0), ...); each is
 * compiled by src/board_desc.c into the table the drivers read (tse_board_desc), so a new board
 * is a new file, never an edit to a driver.  The same file feeds the linker script (the image's
 * origin, below the log), the host checker (tests/boards) and docs/boards.md.
 *
 * What a description must define (docs/boards.md lists them per board):
 *   BOARD_NAME "name"          the name (TSE_BOARD, the image's .tse_board section)
 *   BOARD_PART                 BOARD_PART_F405 or BOARD_PART_F407
 *   BOARD_PACKAGE              BOARD_LQFP64, BOARD_LQFP100 or BOARD_LQFP144
 *   BOARD_FLASH_KIB            the part's flash, KiB (512 or 1024)
 *   BOARD_HSE_HZ               the crystal; the PLL is derived from it (BOARD_PLL_M/N/P/Q may be
 *                              given instead): SYSCLK 168 MHz, USB 48 MHz
 *   BOARD_APP_ADDR             where the image is linked (a flash sector's start: a bootloader
 *                              below it jumps there)
 *   BOARD_PARAM_SECTOR         the first of the parameter log's two sectors (equal sizes), above
 *                              the image
 *   BOARD_STEP1..6, BOARD_DIR1..6, BOARD_LIM1..6   pins, BOARD_PIN(port letter, number)
 *   BOARD_ENABLE1              the drivers' enable; BOARD_ENABLE2..6 more pins driven alike
 *                              (boards with one enable per driver socket), else BOARD_PIN_NONE
 *   BOARD_ENABLE_ACTIVE_HIGH   1: high enables the drivers; 0: low does
 *   BOARD_LIMH1..6             high-end switches (BOARD_PIN_NONE where the board has none),
 *   BOARD_LIMH_FITTED          a mask of those counted (bit k: slide k+1)
 *   BOARD_ESTOP                the e-stop chain's input (its EXTI line is its pin number)
 *   BOARD_LED, BOARD_LED_ACTIVE_HIGH   the status LED (BOARD_PIN_NONE: none)
 *   BOARD_CAN_RX, BOARD_CAN_TX, BOARD_CAN_AF   CAN1's pins and their alternate function
 *   BOARD_BOOT_USART, BOARD_BOOT_TX, BOARD_BOOT_TX_AF   the boot line: USART 1, 2, 3 or 6, its
 *                              TX pin and alternate function
 *   BOARD_SOURCES "..."        the documents the pins were taken from (each pin's comment names
 *                              its own) */
#ifndef TSE_BOARD_DESC_H
#define TSE_BOARD_DESC_H

#include <stdint.h>

/* A pin is its port (0 = A .. 8 = I) times 16 plus its number. */
#define BOARD_PORT_A 0u
#define BOARD_PORT_B 1u
#define BOARD_PORT_C 2u
#define BOARD_PORT_D 3u
#define BOARD_PORT_E 4u
#define BOARD_PORT_F 5u
#define BOARD_PORT_G 6u
#define BOARD_PORT_H 7u
#define BOARD_PORT_I 8u
#define BOARD_PIN(port, n) ((uint8_t)(BOARD_PORT_##port * 16u + (n)))
#define BOARD_PIN_NONE 0xFFu
#define BOARD_PIN_PORT(p) ((unsigned)(p) >> 4)
#define BOARD_PIN_NUM(p) ((unsigned)(p) & 15u)

#define BOARD_PART_F405 405
#define BOARD_PART_F407 407
#define BOARD_LQFP64 64
#define BOARD_LQFP100 100
#define BOARD_LQFP144 144

#define BOARD_SLIDES 6

typedef struct {
    const char *name;
    const char *sources;
    uint16_t part;    /* 405, 407 */
    uint16_t package; /* pins: 64, 100, 144 */
    uint16_t flash_kib;
    uint32_t hse_hz;
    uint8_t pll_m, pll_p, pll_q;
    uint16_t pll_n;
    uint32_t app_addr;
    uint8_t param_sector; /* and param_sector + 1 */
    uint8_t step[BOARD_SLIDES], dir[BOARD_SLIDES], lim[BOARD_SLIDES], limh[BOARD_SLIDES];
    uint8_t enable[BOARD_SLIDES]; /* [0] always; the rest BOARD_PIN_NONE or more enables */
    uint8_t enable_active_high;
    uint8_t limh_fitted;
    uint8_t estop;
    uint8_t led, led_active_high;
    uint8_t can_rx, can_tx, can_af;
    uint8_t boot_usart, boot_tx, boot_tx_af;
    /* Host only (tests/boards/planted): the fault a planted description must be found with. */
    const char *planted_expect;
} board_desc;

/* What a production image says of its board in its .tse_board section (src/board_desc.c), for a
 * tool with only the image (emu/board_props.py wires the emulator's rig to these pins): the
 * string "tse-board:NAME", then the pins as board_desc holds them.  Little-endian, no padding
 * between the fields (all bytes after the two words). */
typedef struct {
    char id[48];        /* "tse-board:NAME", NUL-padded */
    uint32_t hse_hz;
    uint32_t app_addr;
    uint8_t step[BOARD_SLIDES], dir[BOARD_SLIDES], lim[BOARD_SLIDES], enable[BOARD_SLIDES];
    uint8_t enable_active_high, estop, led, led_active_high;
    uint8_t can_rx, can_tx, boot_usart, boot_tx;
} board_identity;

/* The board this image is built for (src/board_desc.c, compiled with its description). */
extern const board_desc tse_board_desc;

/* The flash sectors of the STM32F405/407 (RM0090 table 5): 4 x 16 KiB, 64 KiB, then 128 KiB. */
static inline uint32_t board_sector_addr(unsigned sector)
{
    if (sector <= 4u)
        return 0x08000000u + sector * 0x4000u;
    return 0x08020000u + (sector - 5u) * 0x20000u;
}

static inline uint32_t board_sector_bytes(unsigned sector)
{
    return sector < 4u ? 0x4000u : sector == 4u ? 0x10000u : 0x20000u;
}

#endif
