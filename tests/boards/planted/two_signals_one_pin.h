/* Planted fault (two signals on one pin): gen_f405 with one thing wrong; board_check --planted two_signals_one_pin must
 * find it (tests/boards/CMakeLists.txt). */
#include "../../../hal/stm32f4/boards/gen_f405.h"
#undef BOARD_NAME
#define BOARD_NAME "two_signals_one_pin"
#define BOARD_PLANTED_EXPECT "two signals on one pin"
#undef BOARD_DIR3
#define BOARD_DIR3 BOARD_PIN(C, 0) /* STEP1's pin */
