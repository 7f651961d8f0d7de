/* An update of the application area, command by command (docs/protocol.md, Updating the firmware):
 * the bootloader's logic, plain C over flash_ops and a boot_layout, the same on the board and in
 * the host's simulation and tests.
 *
 * What it promises:
 * - nothing outside the application area's sectors is ever erased or programmed: the bootloader's
 *   sectors and whatever follows the area (the parameter log) stay as they are;
 * - a refused command writes nothing (a flash operation that fails is the one exception: the
 *   update must then start again from BOOT_ERASE);
 * - the image's header is held back in RAM while the blocks are written and programmed only by
 *   boot_update_verify, after the CRC over the whole image read back from flash matched, its
 *   magic word last; so at any moment a power cut leaves either the old image whole (before the
 *   first erase touched it), or an area without a valid header, or the new image whole.
 * Blocks are BOOT_BLOCK_BYTES, announced by BOOT_WRITE and filled by the BOOT_DATA frames that
 * follow it (8 bytes each, in order); a block is checked (number, frames, CRC, and for block 0 the
 * header) when its last frame arrives, and only then programmed. */
#ifndef BOOT_UPDATE_H
#define BOOT_UPDATE_H

#include <stdbool.h>
#include <stdint.h>

#include "boot/image.h"
#include "boot/layout.h"
#include "fw/types.h"
#include "hal_stm32f4/flash_ops.h"

/* 128 frames a block: the host keeps 2 blocks in flight (BOOT_WINDOW_BLOCKS), 258 frames, while
 * the bootloader programs one; an ACK every 1 KiB costs 1 frame in 130. */
#define BOOT_BLOCK_BYTES 1024u
#define BOOT_WINDOW_BLOCKS 2u
_Static_assert(BOOT_BLOCK_BYTES % 8u == 0 && BOOT_BLOCK_BYTES / 8u <= 255u, "a block's frames fit BOOT_WRITE");
_Static_assert(BOOT_BLOCK_BYTES >= BOOT_IMAGE_MIN_LENGTH, "block 0 holds the whole header");

typedef enum {
    BOOT_PHASE_IDLE,    /* nothing erased by this bootloader run, or a flash failure: ERASE first */
    BOOT_PHASE_WRITING, /* erased; taking blocks */
    BOOT_PHASE_DONE     /* verified and marked bootable */
} boot_phase;

/* An answer: reason FW_REASON_NONE for an ACK (with detail), else a REJECT's reason, field, where. */
typedef struct {
    fw_reason reason;
    uint8_t field;
    uint16_t where;
    uint32_t detail;
} boot_verdict;

typedef struct {
    const boot_layout *layout;
    const flash_ops *flash;
    uint32_t board;       /* this board's identity: an image must carry it */
    boot_phase phase;
    uint32_t length;      /* the image's, from BOOT_ERASE */
    uint32_t next_block;  /* the block BOOT_WRITE must name next */
    /* The block being received. */
    bool open;
    uint8_t seq;          /* its BOOT_WRITE's */
    uint8_t frames, got;  /* frames announced and received */
    uint32_t block, crc;
    uint32_t buf[BOOT_BLOCK_BYTES / 4u];
    boot_image_header header; /* block 0's, held back until verified */
    /* Flash operations issued (erase and program calls' words), for the tests' figures. */
    uint32_t erased_sectors, programmed_words;
} boot_update;

/* An update over flash (a region from layout->flash_base, boot/layout.h) for this board. */
void boot_update_init(boot_update *u, const boot_layout *layout, const flash_ops *flash, uint32_t board);

/* BOOT_ERASE: erases the sectors an image of length bytes needs and starts at block 0.  Refused
 * length (0, not whole words, shorter than a header, longer than the area; field 0) or flash.
 * detail: the sectors erased. */
boot_verdict boot_update_erase(boot_update *u, uint32_t length);

/* BOOT_WRITE: opens block `block` of `frames` frames and CRC crc.  A block still open (frames
 * lost) is abandoned first: *abandoned gets its refusal (length) and the function returns 1
 * (*abandoned_seq its sequence number), else 0.  *v: FW_REASON_NONE when the block is open now
 * (its answer comes with its last frame), else the refusal (state, order, address, length). */
int boot_update_write(boot_update *u, uint8_t seq, uint32_t block, uint32_t frames, uint32_t crc, boot_verdict *v,
                      boot_verdict *abandoned, uint8_t *abandoned_seq);

/* BOOT_DATA: 8 bytes of the open block.  Returns 1 when they were its last: the block was
 * checked and programmed, or refused (crc, header, board, flash), *v and *seq its answer;
 * 0 otherwise (frames with no block open are dropped: the rest of a refused block). */
int boot_update_data(boot_update *u, const uint8_t data[8], boot_verdict *v, uint8_t *seq);

/* BOOT_VERIFY: every block in, the CRC read back equal to the header's, then the header
 * programmed (magic last) and the image checked as the boot decision checks it.  Refused state
 * (no update under way), length (blocks missing: where the next), crc, flash. */
boot_verdict boot_update_verify(boot_update *u);

#endif
