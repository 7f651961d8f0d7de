/* gen_f405: the project's own bench map, pins of the 64-pin package only, so that one map fits
 * an STM32F405RG or any F405/F407 board with an 8 MHz crystal (a Netduino Plus 2 serves as a bench
 * controller).  Source of every pin: docs/board.md's wiring (the project's own design, the map
 * pinmap.h held before issue 26), checked against the STM32F405/407 datasheet DocID022152,
 * its pin definitions (LQFP64 column) and alternate function mapping tables. */
#define BOARD_NAME "gen_f405"
#define BOARD_SOURCES "project design (docs/board.md); STM32F405/407 datasheet DocID022152, its pin definitions and alternate function mapping tables"
#define BOARD_PART BOARD_PART_F405 /* STM32F405RGT6 */
#define BOARD_PACKAGE BOARD_LQFP64
#define BOARD_FLASH_KIB 1024
#define BOARD_HSE_HZ 8000000u    /* project design: an 8 MHz crystal on PH0/PH1 */
#define BOARD_APP_ADDR 0x08000000u /* no bootloader: the image from sector 0 */
#define BOARD_PARAM_SECTOR 10      /* sectors 10 and 11 (0x080C0000, 0x080E0000) */

#define BOARD_STEP1 BOARD_PIN(C, 0) /* project design: STEP1..6 on PC0..PC5, one BSRR write */
#define BOARD_STEP2 BOARD_PIN(C, 1) /* project design */
#define BOARD_STEP3 BOARD_PIN(C, 2) /* project design */
#define BOARD_STEP4 BOARD_PIN(C, 3) /* project design */
#define BOARD_STEP5 BOARD_PIN(C, 4) /* project design */
#define BOARD_STEP6 BOARD_PIN(C, 5) /* project design */
#define BOARD_DIR1 BOARD_PIN(C, 6)  /* project design: DIR1..6 on PC6..PC11 */
#define BOARD_DIR2 BOARD_PIN(C, 7)  /* project design */
#define BOARD_DIR3 BOARD_PIN(C, 8)  /* project design */
#define BOARD_DIR4 BOARD_PIN(C, 9)  /* project design */
#define BOARD_DIR5 BOARD_PIN(C, 10) /* project design */
#define BOARD_DIR6 BOARD_PIN(C, 11) /* project design */
#define BOARD_ENABLE1 BOARD_PIN(C, 12) /* project design: one ENABLE for the six drivers */
#define BOARD_ENABLE_ACTIVE_HIGH 1     /* through the 74ACT541 of docs/board.md: high enables */
#define BOARD_LIM1 BOARD_PIN(A, 0) /* project design: LIM1..6 on PA0..PA5 */
#define BOARD_LIM2 BOARD_PIN(A, 1) /* project design */
#define BOARD_LIM3 BOARD_PIN(A, 2) /* project design */
#define BOARD_LIM4 BOARD_PIN(A, 3) /* project design */
#define BOARD_LIM5 BOARD_PIN(A, 4) /* project design */
#define BOARD_LIM6 BOARD_PIN(A, 5) /* project design */
#define BOARD_LIMH1 BOARD_PIN(B, 0)  /* project design: optional high-end switches */
#define BOARD_LIMH2 BOARD_PIN(B, 1)  /* project design */
#define BOARD_LIMH3 BOARD_PIN(B, 12) /* project design */
#define BOARD_LIMH4 BOARD_PIN(B, 13) /* project design */
#define BOARD_LIMH5 BOARD_PIN(B, 14) /* project design */
#define BOARD_LIMH6 BOARD_PIN(B, 15) /* project design */
#define BOARD_LIMH_FITTED 0x00u /* the prototype has none (an open input reads as pressed) */
#define BOARD_ESTOP BOARD_PIN(A, 8) /* project design: EXTI8 */
#define BOARD_LED BOARD_PIN(A, 10)  /* project design: the Netduino Plus 2's user LED */
#define BOARD_LED_ACTIVE_HIGH 1
#define BOARD_CAN_RX BOARD_PIN(B, 8) /* project design; CAN1_RX on PB8 is AF9 (datasheet AF table) */
#define BOARD_CAN_TX BOARD_PIN(B, 9) /* project design; CAN1_TX on PB9 is AF9 (datasheet AF table) */
#define BOARD_CAN_AF 9
#define BOARD_BOOT_USART 1
#define BOARD_BOOT_TX BOARD_PIN(A, 9) /* project design; USART1_TX on PA9 is AF7 (datasheet AF table) */
#define BOARD_BOOT_TX_AF 7
