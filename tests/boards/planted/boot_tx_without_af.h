/* Planted fault (boot-line TX without its USART alternate function): gen_f405 with one thing wrong; board_check --planted boot_tx_without_af must
 * find it (tests/boards/CMakeLists.txt). */
#include "../../../hal/stm32f4/boards/gen_f405.h"
#undef BOARD_NAME
#define BOARD_NAME "boot_tx_without_af"
#define BOARD_PLANTED_EXPECT "boot-line TX without its USART alternate function"
#undef BOARD_BOOT_TX
#define BOARD_BOOT_TX BOARD_PIN(A, 2) /* USART2's TX, not USART1's */
#undef BOARD_LIM3
#define BOARD_LIM3 BOARD_PIN(B, 10) /* PA2 freed for it */
