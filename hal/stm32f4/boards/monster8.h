/* monster8: Makerbase MKS Monster8 V1 (STM32F407VET6, LQFP100, 512 KiB flash, 8 MHz crystal),
 * a 3D-printer board with eight driver sockets and a CAN transceiver, its slides on driver sockets
 * 0..5 (a stepstick in each: STEP, DIR and EN per socket, EN low = enabled).  Sources:
 *   [K] Klipper config/generic-mks-monster8.cfg: the 48 KiB bootloader, the sockets' pins of
 *       stepper_x/y/z and extruder..extruder2, endstops;
 *   [M] MKS-Monster8 repository, Marlin pins_MKS_MONSTER8.h (V2 firmware folder): the same pins,
 *       "PB8 I2C_SCL and CAN_RX", "PB9 I2C_SDA and CAN_TX", SERVO0 (3D TOUCH) PA8;
 *   [R] MKS-Monster8 README.md: STM32F407VET6, 512K flash, "usart1: PA9, PA10";
 *   [U] uCNC boardmap_mks_monster8_v2.h: HSE 8 MHz (from MKS Monster8 V2.0_003 PIN.pdf).
 * The switches: the six endstop connectors X-, Y-, Z-, X+, Y+, Z+ are the low-end switches (the
 * board has no more); X- and X+ are PA14 and PA13, the SWD pins: once the image configures them as
 * inputs a debugger must connect under reset.  PC13..PC15 are in the backup domain (weak outputs,
 * at most 2 MHz, datasheet): enough for 200 kHz steps into a stepstick's input. */
#define BOARD_NAME "monster8"
#define BOARD_SOURCES "Klipper config/generic-mks-monster8.cfg; MKS-Monster8 repository (README.md, Marlin pins_MKS_MONSTER8.h); uCNC boardmap_mks_monster8_v2.h; STM32F405/407 datasheet DocID022152, alternate function mapping table"
#define BOARD_PART BOARD_PART_F407 /* [R] STM32F407VET6 */
#define BOARD_PACKAGE BOARD_LQFP100
#define BOARD_FLASH_KIB 512        /* [R] 512K flash: sectors 0..7 */
#define BOARD_HSE_HZ 8000000u      /* [U] HSE_VALUE 8000000 */
#define BOARD_APP_ADDR 0x0800C000u /* [K] "select the 48KiB bootloader": sector 3 */
#define BOARD_PARAM_SECTOR 6       /* sectors 6 and 7 (0x08040000, 0x08060000): the last two */

#define BOARD_STEP1 BOARD_PIN(C, 14) /* [K] stepper_x step_pin PC14 (Driver0) */
#define BOARD_STEP2 BOARD_PIN(E, 5)  /* [K] stepper_y step_pin PE5 (Driver1) */
#define BOARD_STEP3 BOARD_PIN(E, 1)  /* [K] stepper_z step_pin PE1 (Driver2) */
#define BOARD_STEP4 BOARD_PIN(B, 5)  /* [K] extruder step_pin PB5 (Driver3) */
#define BOARD_STEP5 BOARD_PIN(D, 6)  /* [K] extruder1 step_pin PD6 (Driver4) */
#define BOARD_STEP6 BOARD_PIN(D, 2)  /* [K] extruder2 step_pin PD2 (Driver5) */
#define BOARD_DIR1 BOARD_PIN(C, 13)  /* [K] stepper_x dir_pin PC13 */
#define BOARD_DIR2 BOARD_PIN(E, 4)   /* [K] stepper_y dir_pin PE4 */
#define BOARD_DIR3 BOARD_PIN(E, 0)   /* [K] stepper_z dir_pin PE0 */
#define BOARD_DIR4 BOARD_PIN(B, 4)   /* [K] extruder dir_pin PB4 */
#define BOARD_DIR5 BOARD_PIN(D, 5)   /* [K] extruder1 dir_pin PD5 */
#define BOARD_DIR6 BOARD_PIN(D, 1)   /* [K] extruder2 dir_pin PD1 */
#define BOARD_ENABLE1 BOARD_PIN(C, 15) /* [K] stepper_x and stepper_y enable_pin !PC15 (shared) */
#define BOARD_ENABLE2 BOARD_PIN(E, 2)  /* [K] stepper_z enable_pin !PE2 */
#define BOARD_ENABLE3 BOARD_PIN(B, 6)  /* [K] extruder enable_pin !PB6 */
#define BOARD_ENABLE4 BOARD_PIN(D, 7)  /* [K] extruder1 enable_pin !PD7 */
#define BOARD_ENABLE5 BOARD_PIN(D, 3)  /* [K] extruder2 enable_pin !PD3 */
#define BOARD_ENABLE_ACTIVE_HIGH 0     /* [K] "!": a stepstick's EN is active low */
#define BOARD_LIM1 BOARD_PIN(A, 14) /* [K] X- endstop PA14 (SWCLK) */
#define BOARD_LIM2 BOARD_PIN(A, 15) /* [K] Y- endstop PA15 */
#define BOARD_LIM3 BOARD_PIN(B, 13) /* [K] Z- endstop PB13 */
#define BOARD_LIM4 BOARD_PIN(A, 13) /* [K] "PA13 for X-max" (SWDIO) */
#define BOARD_LIM5 BOARD_PIN(C, 5)  /* [K] "PC5 for Y-max" */
#define BOARD_LIM6 BOARD_PIN(B, 12) /* [K] "PB12 for Z-max" */
#define BOARD_LIMH1 BOARD_PIN_NONE
#define BOARD_LIMH2 BOARD_PIN_NONE
#define BOARD_LIMH3 BOARD_PIN_NONE
#define BOARD_LIMH4 BOARD_PIN_NONE
#define BOARD_LIMH5 BOARD_PIN_NONE
#define BOARD_LIMH6 BOARD_PIN_NONE
#define BOARD_LIMH_FITTED 0x00u
#define BOARD_ESTOP BOARD_PIN(A, 8) /* [M] SERVO0_PIN PA8, the 3D TOUCH connector; EXTI8 */
#define BOARD_LED BOARD_PIN_NONE    /* no user LED on a GPIO in [K], [M] or [U] */
#define BOARD_LED_ACTIVE_HIGH 1
#define BOARD_CAN_RX BOARD_PIN(B, 8) /* [M] "I2C_SCL and CAN_RX" PB8 (AF9, datasheet AF table) */
#define BOARD_CAN_TX BOARD_PIN(B, 9) /* [M] "I2C_SDA and CAN_TX" PB9 (AF9, datasheet AF table) */
#define BOARD_CAN_AF 9
#define BOARD_BOOT_USART 1
#define BOARD_BOOT_TX BOARD_PIN(A, 9) /* [R] usart1 PA9 (AF7, datasheet AF table) */
#define BOARD_BOOT_TX_AF 7
