/* Planted fault (CAN pin without its alternate function): gen_f405 with one thing wrong; board_check --planted can_without_af must
 * find it (tests/boards/CMakeLists.txt). */
#include "../../../hal/stm32f4/boards/gen_f405.h"
#undef BOARD_NAME
#define BOARD_NAME "can_without_af"
#define BOARD_PLANTED_EXPECT "CAN pin without its alternate function"
#undef BOARD_CAN_RX
#define BOARD_CAN_RX BOARD_PIN(B, 7) /* PB7 has no CAN1_RX */
