/* The board descriptions a host program was linked with (cmake/TseBoards.cmake,
 * tse_board_desc_set): every board of hal/stm32f4/boards, or the planted faulty ones of
 * tests/boards/planted. */
#ifndef TSE_BOARD_LIST_H
#define TSE_BOARD_LIST_H

#include "hal_stm32f4/board_desc.h"

extern const board_desc *const board_descs[];
extern const unsigned board_desc_count;

#endif
