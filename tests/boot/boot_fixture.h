/* What the bootloader's tests share: images built by hand, a reference CRC-32 written apart from
 * the code under test (bitwise, from the polynomial), the F405's first six sectors in a simulated
 * flash, and a host that sends an image through the update's commands as tsectl does. */
#ifndef TSE_TEST_BOOT_FIXTURE_H
#define TSE_TEST_BOOT_FIXTURE_H

#include <stdbool.h>
#include <stdint.h>

#include "boot/update.h"
#include "sim_flash.h"

/* RM0090's sectors 0..5 (16, 16, 16, 16, 64, 128 KiB: 256 KiB): the bootloader in sector 0 and
 * the application area in 1..5 (240 KiB from 0x08004000), worked by hand. */
#define FX_APP_OFFSET 0x4000u
#define FX_APP_BYTES (3u * 0x4000u + 0x10000u + 0x20000u)
#define FX_APP_START (0x08000000u + FX_APP_OFFSET)
#define FX_NSECTORS 6u

#define FX_BOARD_NAME "tse-test-board"
#define FX_IMAGE_MAX FX_APP_BYTES

/* The reference CRC-32: bit by bit from the reflected polynomial 0xEDB88320. */
uint32_t fx_crc32(const uint8_t *p, uint32_t n);

/* An image of length bytes (a multiple of 4) for board (a boot_board_id) and version, its
 * contents drawn from seed, its vector table's reset vector inside it, its header filled with the
 * CRC computed by fx_crc32 (the crc word left out). */
void fx_image(uint8_t *img, uint32_t length, uint32_t board, uint32_t version, uint32_t seed);

/* The flash of FX_NSECTORS sectors, erased, with the bootloader's sector filled with a pattern
 * (fx_boot_intact says whether it is still there). */
void fx_flash_init(sim_flash *f, uint32_t seed);
bool fx_boot_intact(const sim_flash *f);
/* An image placed in the application area as a finished update leaves it (all words programmed). */
void fx_flash_install(sim_flash *f, const uint8_t *img, uint32_t length);

/* What a host's run of an update got. */
typedef struct {
    fw_reason erase, verify;     /* their answers */
    uint32_t blocks_acked;
    fw_reason first_block_refusal; /* FW_REASON_NONE when every block was taken */
    uint32_t refused_block;
} fx_run;

/* Sends the image through u as a host does: ERASE(length), each block's WRITE and frames, VERIFY;
 * it stops at the first refusal. */
fx_run fx_send(boot_update *u, const uint8_t *img, uint32_t length);

/* Sends block b of img (WRITE with the given frames and crc, then `frames` frames of data from the
 * block's offset); returns the answer (FW_REASON_NONE ACK), *answered whether one came. */
boot_verdict fx_block(boot_update *u, const uint8_t *img, uint32_t b, uint32_t frames, uint32_t crc, bool *answered);

#endif
