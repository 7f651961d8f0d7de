/* Planted fault (parameter log overlaps the application image): gen_f405 with one thing wrong; board_check --planted param_log_overlaps_app must
 * find it (tests/boards/CMakeLists.txt). */
#include "../../../hal/stm32f4/boards/gen_f405.h"
#undef BOARD_NAME
#define BOARD_NAME "param_log_overlaps_app"
#define BOARD_PLANTED_EXPECT "parameter log overlaps the application image"
#undef BOARD_APP_ADDR
#define BOARD_APP_ADDR 0x08010000u /* sector 4 */
#undef BOARD_PARAM_SECTOR
#define BOARD_PARAM_SECTOR 5 /* 64 KiB above it: under the 96 KiB image */
