/* Where the bootloader and the application live in flash, as a board describes it.
 *
 * The flash is seen through flash_ops (hal_stm32f4/flash_ops.h) as one region from flash_base:
 * erase(k) erases the device's sector k, program takes offsets from flash_base.  The layout says
 * which sectors are the bootloader's (0 .. boot_sectors - 1, never erased by an update) and
 * which the application area's (each with its number, its offset from flash_base and its size,
 * in address order, the area's start on a sector's start).  A board description fills one,
 * boot_layout_stm32f4 for the F405/F407's sectors; boot_layout_check says whether one can be. */
#ifndef BOOT_LAYOUT_H
#define BOOT_LAYOUT_H

#include <stdint.h>

#define BOOT_LAYOUT_MAX_SECTORS 12u

typedef struct {
    uint32_t offset; /* from flash_base */
    uint32_t bytes;
    uint8_t number;  /* the device's sector number, as flash_ops.erase takes it */
} boot_sector;

typedef struct {
    uint32_t flash_base;   /* the address of the region's first byte (0x08000000 on the F4) */
    uint32_t boot_bytes;   /* the bootloader's sectors: [flash_base, flash_base + boot_bytes) */
    uint32_t app_offset;   /* the application area: [app_offset, app_offset + app_bytes) of the region */
    uint32_t app_bytes;
    uint8_t boot_sectors;  /* device sectors 0 .. boot_sectors - 1 are the bootloader's */
    uint8_t nsectors;      /* the application area's sectors */
    boot_sector sectors[BOOT_LAYOUT_MAX_SECTORS];
} boot_layout;

/* The STM32F405/407 (RM0090 3.3, 1 MiB: sectors 0..3 of 16 KiB, 4 of 64 KiB, 5..11 of 128 KiB):
 * the bootloader in sectors 0 .. boot_sectors - 1, the application area in boot_sectors ..
 * end_sector - 1 (sectors from end_sector on are another's: the parameter log's 10 and 11).
 * Returns 0, or -1 for sector numbers that do not make a layout (nothing for the bootloader or
 * the application, beyond sector 12). */
int boot_layout_stm32f4(boot_layout *l, unsigned boot_sectors, unsigned end_sector);

/* 0 when l is a layout an update can run in: at least one application sector, the sectors in
 * address order with no gap, the first at app_offset and the last ending at app_offset +
 * app_bytes, none numbered below boot_sectors, and the area after the bootloader's bytes;
 * -1 otherwise. */
int boot_layout_check(const boot_layout *l);

/* The application sectors an image of length bytes needs (its first sectors in order), or 0 for
 * a length of 0 or one beyond the area. */
unsigned boot_layout_sectors_for(const boot_layout *l, uint32_t length);

#endif
