/* Planted fault (pin not on the package): gen_f405 with one thing wrong; board_check --planted pin_not_on_package must
 * find it (tests/boards/CMakeLists.txt). */
#include "../../../hal/stm32f4/boards/gen_f405.h"
#undef BOARD_NAME
#define BOARD_NAME "pin_not_on_package"
#define BOARD_PLANTED_EXPECT "pin not on the package"
#undef BOARD_STEP1
#define BOARD_STEP1 BOARD_PIN(E, 0) /* no port E in LQFP64 */
