/* Planted fault (not sector-aligned): gen_f405 with one thing wrong; board_check --planted app_not_sector_aligned must
 * find it (tests/boards/CMakeLists.txt). */
#include "../../../hal/stm32f4/boards/gen_f405.h"
#undef BOARD_NAME
#define BOARD_NAME "app_not_sector_aligned"
#define BOARD_PLANTED_EXPECT "not sector-aligned"
#undef BOARD_APP_ADDR
#define BOARD_APP_ADDR 0x08001000u /* inside sector 0 */
