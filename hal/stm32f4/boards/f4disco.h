/* f4disco: ST's STM32F4DISCOVERY kit (STM32F407VGT6, LQFP100, 8 MHz crystal X2), with the
 * slides on pins its on-board parts leave alone.  Taken by the kit, as issue 26 quotes ST UM1472
 * ("Discovery kit with STM32F407VG MCU": its table "MCU pin description versus board function")
 * and as xpcc's STM32F4DISCOVERY example confirms for the LEDs, button and USB pins: PA0 user
 * button B1; PC0 USB OTG power switch enable, PD5 its overcurrent (LED LD8); PA9 VBUS (LED LD7),
 * PA10 ID, PA11/PA12 USB DM/DP; audio codec CS43L22 on PA4, PB6, PB9, PC7, PC10, PC12, PD4; the
 * accelerometer LIS302DL/LIS3DSH on PA5..PA7, PE3; LEDs LD3..LD6 on PD12..PD15; SWD PA13/PA14;
 * the crystal on PH0/PH1; and, from our recollection of UM1472 (not checked), the accelerometer's
 * interrupts PE0/PE1, the microphone MP45DT02 on PB10/PC3 and SWO on PB3.  Every pin below is none of those ("UM1472 list: no on-board use").  UM1472 itself
 * was not read for this file: check a pin against its table before wiring it. */
#define BOARD_NAME "f4disco"
#define BOARD_SOURCES "ST UM1472 (STM32F4DISCOVERY user manual), its on-board pins as issue 26 lists them; xpcc STM32F4DISCOVERY example (LEDs, button, USB); STM32F405/407 datasheet DocID022152, alternate function mapping table"
#define BOARD_PART BOARD_PART_F407 /* STM32F407VGT6 (UM1472) */
#define BOARD_PACKAGE BOARD_LQFP100
#define BOARD_FLASH_KIB 1024
#define BOARD_HSE_HZ 8000000u      /* UM1472: X2, 8 MHz */
#define BOARD_APP_ADDR 0x08000000u /* programmed by the kit's ST-LINK: no bootloader */
#define BOARD_PARAM_SECTOR 10

#define BOARD_STEP1 BOARD_PIN(E, 7)  /* UM1472 list: no on-board use; STEP1..6 one port, one write */
#define BOARD_STEP2 BOARD_PIN(E, 8)  /* UM1472 list: no on-board use */
#define BOARD_STEP3 BOARD_PIN(E, 9)  /* UM1472 list: no on-board use */
#define BOARD_STEP4 BOARD_PIN(E, 10) /* UM1472 list: no on-board use */
#define BOARD_STEP5 BOARD_PIN(E, 11) /* UM1472 list: no on-board use */
#define BOARD_STEP6 BOARD_PIN(E, 12) /* UM1472 list: no on-board use */
#define BOARD_DIR1 BOARD_PIN(D, 6)  /* UM1472 list: PD6 no on-board use */
#define BOARD_DIR2 BOARD_PIN(D, 7)  /* UM1472 list: no on-board use */
#define BOARD_DIR3 BOARD_PIN(D, 8)  /* UM1472 list: no on-board use */
#define BOARD_DIR4 BOARD_PIN(D, 9)  /* UM1472 list: no on-board use */
#define BOARD_DIR5 BOARD_PIN(D, 10) /* UM1472 list: no on-board use */
#define BOARD_DIR6 BOARD_PIN(D, 11) /* UM1472 list: no on-board use */
#define BOARD_ENABLE1 BOARD_PIN(E, 13) /* UM1472 list: no on-board use */
#define BOARD_ENABLE_ACTIVE_HIGH 1     /* the buffer of docs/board.md */
#define BOARD_LIM1 BOARD_PIN(C, 1) /* UM1472 list: PC1 no on-board use */
#define BOARD_LIM2 BOARD_PIN(C, 2) /* UM1472 list: no on-board use */
#define BOARD_LIM3 BOARD_PIN(C, 4) /* UM1472 list: no on-board use */
#define BOARD_LIM4 BOARD_PIN(C, 5) /* UM1472 list: no on-board use */
#define BOARD_LIM5 BOARD_PIN(C, 6) /* UM1472 list: no on-board use */
#define BOARD_LIM6 BOARD_PIN(C, 8) /* UM1472 list: no on-board use */
#define BOARD_LIMH1 BOARD_PIN_NONE
#define BOARD_LIMH2 BOARD_PIN_NONE
#define BOARD_LIMH3 BOARD_PIN_NONE
#define BOARD_LIMH4 BOARD_PIN_NONE
#define BOARD_LIMH5 BOARD_PIN_NONE
#define BOARD_LIMH6 BOARD_PIN_NONE
#define BOARD_LIMH_FITTED 0x00u
#define BOARD_ESTOP BOARD_PIN(E, 15) /* UM1472 list: no on-board use; EXTI15 */
#define BOARD_LED BOARD_PIN(D, 12)   /* UM1472 list, xpcc: LD4, green, lit by a high level */
#define BOARD_LED_ACTIVE_HIGH 1
#define BOARD_CAN_RX BOARD_PIN(D, 0) /* UM1472 list: PD0 no on-board use; CAN1_RX AF9 (datasheet AF table) */
#define BOARD_CAN_TX BOARD_PIN(D, 1) /* UM1472 list: PD1 no on-board use; CAN1_TX AF9 (datasheet AF table) */
#define BOARD_CAN_AF 9
#define BOARD_BOOT_USART 2 /* USART1's pins PA9 (VBUS) and PB6 (codec I2C) are taken */
#define BOARD_BOOT_TX BOARD_PIN(A, 2) /* UM1472 list: PA2 no on-board use; USART2_TX AF7 (datasheet AF table) */
#define BOARD_BOOT_TX_AF 7
