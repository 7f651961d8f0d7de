/* What the bootloader and the application share on the STM32F405/407 (boot/stm32f4): where the
 * update request lives (boot/request.h), the layout, and the board's identity. */
#ifndef BOOT_F4_H
#define BOOT_F4_H

#include "boot/layout.h"
#include "boot/request.h"

/* The last 16 bytes of SRAM: both linker scripts leave them out, so no start-up code clears them
 * and a reset keeps them. */
#define BOOT_F4_REQUEST ((volatile boot_request *)0x2001FFF0u)
_Static_assert(sizeof(boot_request) <= 16, "the request fits the bytes kept for it");

/* The bootloader in sector 0 (16 KiB), the application in sectors 1..9, the parameter log in 10
 * and 11 (docs/board.md).  A board description may say otherwise. */
#ifndef BOOT_F4_BOOT_SECTORS
#define BOOT_F4_BOOT_SECTORS 1u
#endif
#ifndef BOOT_F4_APP_END_SECTOR
#define BOOT_F4_APP_END_SECTOR 10u
#endif

/* The board's name, whose CRC-32 an image's header must carry: TSE_BOARD_NAME, which
 * boot/stm32f4/CMakeLists.txt gives as the build's TSE_BOARD. */
#ifndef TSE_BOARD_NAME
#error "TSE_BOARD_NAME: the board's name, given by boot/stm32f4/CMakeLists.txt"
#endif

#endif
