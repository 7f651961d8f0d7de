/* A region of flash as a writer sees it, read through memory and changed only through erase and
 * program.  The parameter log's (param_log.h) is two equal sectors, one after the other
 * (sector_bytes each); the bootloader's update (boot/update.h) sees the device from its first
 * sector, its sectors' sizes in a boot_layout (sector_bytes unused, 0).
 *
 * Both are written against this and nothing else, so that the same code runs over the board's
 * flash controller (flash_f4.h) and over the simulated NOR flash of the tests.
 *
 * Semantics every implementation keeps (NOR flash):
 * - erase sets every bit of one sector to 1 (every word reads 0xFFFFFFFF);
 * - program can only clear bits, one 32-bit word at a time, and each word at most once
 *   between two erases: the log never asks for more;
 * - an operation that returns an error may have done part of its work (a power cut, a torn
 *   word): the log assumes nothing about the words it touched. */
#ifndef TSE_FLASH_OPS_H
#define TSE_FLASH_OPS_H

#include <stdint.h>

/* What erase and program return. */
enum {
    FLASH_OPS_OK = 0,
    FLASH_OPS_EARG = -1,     /* outside the region, misaligned, or no such sector */
    FLASH_OPS_ETIMEOUT = -2, /* the controller stayed busy past its bound */
    FLASH_OPS_EFAIL = -3     /* the controller refused or failed it (error flags, power lost) */
};

typedef struct {
    void *ctx;
    /* The region's contents, memory-mapped (a parameter log's: sector 0 is words
     * [0, sector_bytes / 4), sector 1 the next sector_bytes / 4 words).  Reads see every
     * completed erase and program. */
    const uint32_t *mem;
    uint32_t sector_bytes; /* a multiple of 4 */
    /* Erases a sector of the region: 0 or 1 of a parameter log's, a device sector number of the
     * bootloader's. */
    int (*erase)(void *ctx, uint32_t sector);
    /* Programs n words at byte offset `offset` from the region's start (a multiple of 4),
     * in increasing address order, each word once. */
    int (*program)(void *ctx, uint32_t offset, const uint32_t *words, uint32_t n);
} flash_ops;

#endif
