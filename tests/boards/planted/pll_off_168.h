/* Planted fault (not 168 and 48): gen_f405 with one thing wrong; board_check --planted pll_off_168 must
 * find it (tests/boards/CMakeLists.txt). */
#include "../../../hal/stm32f4/boards/gen_f405.h"
#undef BOARD_NAME
#define BOARD_NAME "pll_off_168"
#define BOARD_PLANTED_EXPECT "not 168 and 48"
#undef BOARD_HSE_HZ
#define BOARD_HSE_HZ 12000000u
#define BOARD_PLL_M 4u /* an 8 MHz crystal's M: VCO in 3 MHz */
#define BOARD_PLL_N 168u
#define BOARD_PLL_P 2u
#define BOARD_PLL_Q 7u
