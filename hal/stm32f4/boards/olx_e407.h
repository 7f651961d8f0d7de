/* olx_e407: Olimex STM32-E407 (STM32F407ZGT6, LQFP144, 12 MHz crystal).  On-board parts, from
 * NuttX's board support boards/arm/stm32/olimex-stm32-e407 (include/board.h and
 * src/olimex-stm32-e407.h; Olimex's schematic itself was not read for this file): the Ethernet PHY
 * LAN8710 on PA2, PA3, PA7, PC1, PC4, PC5, PG6, PG11, PG13, PG14 (and, as the issue lists its RMII
 * pins, PA1, PB11..PB13); USB OTG FS on PA9, PA11, PA12, PB0, PB1; USB OTG HS on PA8, PB13, PB14,
 * PB15, PF11; the SD card (SDIO) on PC8..PC12, PD2; button BUT on PA0; the status LED on PC13; SWD
 * PA13/PA14; the crystal on PH0/PH1.  CAN1 is on PB8/PB9 and USART1 on PB6/PB7 (the same files).
 * The slides take ports E and F, which none of those use. */
#define BOARD_NAME "olx_e407"
#define BOARD_SOURCES "NuttX olimex-stm32-e407 board support (include/board.h, src/olimex-stm32-e407.h); STM32F405/407 datasheet DocID022152, alternate function mapping table"
#define BOARD_PART BOARD_PART_F407 /* STM32F407ZGT6 (board.h) */
#define BOARD_PACKAGE BOARD_LQFP144
#define BOARD_FLASH_KIB 1024
#define BOARD_HSE_HZ 12000000u     /* board.h: "On-board crystal frequency is 12MHz" */
#define BOARD_APP_ADDR 0x08000000u /* programmed through JTAG/SWD: no bootloader */
#define BOARD_PARAM_SECTOR 10

#define BOARD_STEP1 BOARD_PIN(E, 0) /* NuttX e407: PE0 unused on board; STEP1..6 one port */
#define BOARD_STEP2 BOARD_PIN(E, 1) /* NuttX e407: unused on board */
#define BOARD_STEP3 BOARD_PIN(E, 2) /* NuttX e407: unused on board */
#define BOARD_STEP4 BOARD_PIN(E, 3) /* NuttX e407: unused on board */
#define BOARD_STEP5 BOARD_PIN(E, 4) /* NuttX e407: unused on board */
#define BOARD_STEP6 BOARD_PIN(E, 5) /* NuttX e407: unused on board */
#define BOARD_DIR1 BOARD_PIN(E, 6)  /* NuttX e407: unused on board */
#define BOARD_DIR2 BOARD_PIN(E, 7)  /* NuttX e407: unused on board */
#define BOARD_DIR3 BOARD_PIN(E, 8)  /* NuttX e407: unused on board */
#define BOARD_DIR4 BOARD_PIN(E, 9)  /* NuttX e407: unused on board */
#define BOARD_DIR5 BOARD_PIN(E, 10) /* NuttX e407: unused on board */
#define BOARD_DIR6 BOARD_PIN(E, 11) /* NuttX e407: unused on board */
#define BOARD_ENABLE1 BOARD_PIN(E, 12) /* NuttX e407: unused on board */
#define BOARD_ENABLE_ACTIVE_HIGH 1     /* the buffer of docs/board.md */
#define BOARD_LIM1 BOARD_PIN(F, 0) /* NuttX e407: PF0 unused on board */
#define BOARD_LIM2 BOARD_PIN(F, 1) /* NuttX e407: unused on board */
#define BOARD_LIM3 BOARD_PIN(F, 2) /* NuttX e407: unused on board */
#define BOARD_LIM4 BOARD_PIN(F, 3) /* NuttX e407: unused on board */
#define BOARD_LIM5 BOARD_PIN(F, 4) /* NuttX e407: unused on board */
#define BOARD_LIM6 BOARD_PIN(F, 5) /* NuttX e407: unused on board */
#define BOARD_LIMH1 BOARD_PIN(F, 6)  /* NuttX e407: unused on board */
#define BOARD_LIMH2 BOARD_PIN(F, 7)  /* NuttX e407: unused on board */
#define BOARD_LIMH3 BOARD_PIN(F, 8)  /* NuttX e407: unused on board */
#define BOARD_LIMH4 BOARD_PIN(F, 9)  /* NuttX e407: unused on board */
#define BOARD_LIMH5 BOARD_PIN(F, 10) /* NuttX e407: unused on board (PF11 is OTG HS overcurrent) */
#define BOARD_LIMH6 BOARD_PIN(F, 12) /* NuttX e407: unused on board */
#define BOARD_LIMH_FITTED 0x00u
#define BOARD_ESTOP BOARD_PIN(E, 13) /* NuttX e407: unused on board; EXTI13 */
#define BOARD_LED BOARD_PIN(C, 13)   /* src/olimex-stm32-e407.h: GPIO_LED_STATUS, PC13, high = on */
#define BOARD_LED_ACTIVE_HIGH 1
#define BOARD_CAN_RX BOARD_PIN(B, 8) /* board.h: GPIO_CAN1_RX_2, PB8 (AF9, datasheet AF table) */
#define BOARD_CAN_TX BOARD_PIN(B, 9) /* board.h: GPIO_CAN1_TX_2, PB9 (AF9, datasheet AF table) */
#define BOARD_CAN_AF 9
#define BOARD_BOOT_USART 1
#define BOARD_BOOT_TX BOARD_PIN(B, 6) /* board.h: GPIO_USART1_TX_2, PB6 (AF7, datasheet AF table) */
#define BOARD_BOOT_TX_AF 7
