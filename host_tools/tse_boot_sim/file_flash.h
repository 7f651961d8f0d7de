/* A board's flash kept in a file, as flash_ops (hal_stm32f4/flash_ops.h) over a boot_layout's
 * region: for tse-boot-sim, so that what an update wrote survives the simulator's end as it
 * survives a board's power cycle.  NOR rules as the board's: erase sets a sector to 0xFF, program
 * only clears bits (a program that would set one fails, nothing written).  Every operation is
 * written through to the file before it returns. */
#ifndef TSE_FILE_FLASH_H
#define TSE_FILE_FLASH_H

#include <stdint.h>

#include "boot/layout.h"
#include "hal_stm32f4/flash_ops.h"

/* Bytes from the region's start to the end of the application area: what the file holds. */
#define FILE_FLASH_MAX_BYTES 0x100000u

typedef struct {
    int fd;
    uint32_t bytes;
    const boot_layout *layout;
    _Alignas(4) uint8_t mem[FILE_FLASH_MAX_BYTES];
} file_flash;

/* Opens (creating, erased, with a bootloader's pattern in its first sectors) the file at path for
 * the region of layout.  Returns 0, or -1 with errno set. */
int file_flash_open(file_flash *f, const char *path, const boot_layout *layout);
flash_ops file_flash_ops(file_flash *f);

#endif
