#include "boot/update.h"

#include <string.h>

#include "boot/crc32.h"

#define HEADER_WORD0 (BOOT_IMAGE_HEADER_OFFSET / 4u)
#define HEADER_WORDS ((uint32_t)sizeof(boot_image_header) / 4u)

static boot_verdict refuse(fw_reason r, uint8_t field, uint32_t where)
{
    return (boot_verdict){r, field, (uint16_t)(where > 65535u ? 65535u : where), 0};
}

static boot_verdict accept(uint32_t detail)
{
    return (boot_verdict){FW_REASON_NONE, 0, 0, detail};
}

static const uint8_t *app_bytes(const boot_update *u)
{
    return (const uint8_t *)u->flash->mem + u->layout->app_offset;
}

void boot_update_init(boot_update *u, const boot_layout *layout, const flash_ops *flash, uint32_t board)
{
    memset(u, 0, sizeof *u);
    u->layout = layout;
    u->flash = flash;
    u->board = board;
}

boot_verdict boot_update_erase(boot_update *u, uint32_t length)
{
    const boot_layout *l = u->layout;
    if (length % 4u != 0 || length < BOOT_IMAGE_MIN_LENGTH || length > l->app_bytes)
        return refuse(FW_REASON_LENGTH, 1, 0);
    u->phase = BOOT_PHASE_IDLE; /* until every sector is erased */
    u->open = false;
    const unsigned n = boot_layout_sectors_for(l, length);
    for (unsigned i = 0; i < n; ++i) {
        const uint8_t k = l->sectors[i].number;
        if (k < l->boot_sectors) /* boot_layout_check refuses such a layout; never erase ourselves */
            return refuse(FW_REASON_FLASH, 0, k);
        ++u->erased_sectors;
        if (u->flash->erase(u->flash->ctx, k) != FLASH_OPS_OK)
            return refuse(FW_REASON_FLASH, 0, k);
    }
    u->phase = BOOT_PHASE_WRITING;
    u->length = length;
    u->next_block = 0;
    return accept(n);
}

/* The bytes of block b of the image: a whole block but for the last. */
static uint32_t block_bytes_of(const boot_update *u, uint32_t b)
{
    const uint32_t off = b * BOOT_BLOCK_BYTES;
    return u->length - off < BOOT_BLOCK_BYTES ? u->length - off : BOOT_BLOCK_BYTES;
}

int boot_update_write(boot_update *u, uint8_t seq, uint32_t block, uint32_t frames, uint32_t crc, boot_verdict *v,
                      boot_verdict *abandoned, uint8_t *abandoned_seq)
{
    int gave_up = 0;
    if (u->open) {
        /* Its frames did not all come: refused, nothing of it written, and the host, whose window
         * holds it, sends again from it. */
        u->open = false;
        *abandoned = refuse(FW_REASON_LENGTH, 0, u->got);
        *abandoned_seq = u->seq;
        gave_up = 1;
    }
    if (u->phase != BOOT_PHASE_WRITING) {
        *v = refuse(FW_REASON_STATE, 0, 0);
    } else if (block >= (u->length + BOOT_BLOCK_BYTES - 1u) / BOOT_BLOCK_BYTES) {
        *v = refuse(FW_REASON_ADDRESS, 1, block);
    } else if (block != u->next_block) {
        *v = refuse(FW_REASON_ORDER, (uint8_t)u->next_block, u->next_block);
    } else if (frames != (block_bytes_of(u, block) + 7u) / 8u) {
        *v = refuse(FW_REASON_LENGTH, 2, (block_bytes_of(u, block) + 7u) / 8u);
    } else {
        u->open = true;
        u->seq = seq;
        u->block = block;
        u->frames = (uint8_t)frames;
        u->got = 0;
        u->crc = crc;
        *v = accept(block);
    }
    return gave_up;
}

/* Block 0's header against the update: a header, of our version, for this length and board. */
static boot_verdict check_header(boot_update *u)
{
    boot_image_header h;
    boot_image_header_read((const uint8_t *)u->buf, &h);
    if (h.magic != BOOT_IMAGE_MAGIC || h.header_version != BOOT_IMAGE_HEADER_VERSION)
        return refuse(FW_REASON_HEADER, 0, 0);
    if (h.length != u->length)
        return refuse(FW_REASON_HEADER, 1, 0);
    if (h.board != u->board)
        return refuse(FW_REASON_BOARD, 0, 0);
    u->header = h;
    return accept(0);
}

/* Programs words [from, to) of the block's buffer at the image's byte offset base, in runs,
 * leaving alone the words that read erased (0xFFFFFFFF) and, in block 0, the header. */
static int program_block(boot_update *u, uint32_t base, uint32_t nwords)
{
    uint32_t i = 0;
    while (i < nwords) {
        const bool hold = base == 0 && i >= HEADER_WORD0 && i < HEADER_WORD0 + HEADER_WORDS;
        if (hold || u->buf[i] == 0xFFFFFFFFu) {
            ++i;
            continue;
        }
        uint32_t j = i + 1u;
        while (j < nwords && u->buf[j] != 0xFFFFFFFFu && !(base == 0 && j == HEADER_WORD0))
            ++j;
        u->programmed_words += j - i;
        if (u->flash->program(u->flash->ctx, u->layout->app_offset + base + 4u * i, &u->buf[i], j - i) !=
            FLASH_OPS_OK)
            return -1;
        i = j;
    }
    return 0;
}

int boot_update_data(boot_update *u, const uint8_t data[8], boot_verdict *v, uint8_t *seq)
{
    if (!u->open)
        return 0;
    memcpy((uint8_t *)u->buf + 8u * u->got, data, 8);
    if (++u->got < u->frames)
        return 0;
    u->open = false;
    *seq = u->seq;
    const uint32_t bytes = block_bytes_of(u, u->block);
    if (crc32_update(0, u->buf, bytes) != u->crc) {
        *v = refuse(FW_REASON_CRC, 0, u->block);
        return 1;
    }
    if (u->block == 0) {
        *v = check_header(u);
        if (v->reason != FW_REASON_NONE)
            return 1;
    }
    if (program_block(u, u->block * BOOT_BLOCK_BYTES, bytes / 4u) != 0) {
        u->phase = BOOT_PHASE_IDLE;
        *v = refuse(FW_REASON_FLASH, 0, u->block);
        return 1;
    }
    ++u->next_block;
    *v = accept(u->block);
    return 1;
}

boot_verdict boot_update_verify(boot_update *u)
{
    const boot_layout *l = u->layout;
    boot_image_header h;
    if (u->phase == BOOT_PHASE_DONE)
        return boot_image_check(app_bytes(u), l->app_bytes, l->flash_base + l->app_offset, u->board, &h) ==
                       BOOT_IMAGE_OK
                   ? accept(0)
                   : refuse(FW_REASON_CRC, 0, 0);
    if (u->phase != BOOT_PHASE_WRITING)
        return refuse(FW_REASON_STATE, 0, 0);
    if (u->open || u->next_block * BOOT_BLOCK_BYTES < u->length)
        return refuse(FW_REASON_LENGTH, 0, u->next_block);
    if (boot_image_crc(app_bytes(u), u->length, &u->header) != u->header.crc) {
        u->phase = BOOT_PHASE_IDLE; /* what flash holds is wrong and cannot be written again */
        return refuse(FW_REASON_CRC, 0, 0);
    }
    /* The header but its magic, then the magic: until that last word is whole, no header. */
    const uint32_t *w = (const uint32_t *)&u->header;
    const uint32_t at = l->app_offset + BOOT_IMAGE_HEADER_OFFSET;
    for (uint32_t i = 1; i < HEADER_WORDS; ++i) {
        if (w[i] == 0xFFFFFFFFu)
            continue;
        ++u->programmed_words;
        if (u->flash->program(u->flash->ctx, at + 4u * i, &w[i], 1) != FLASH_OPS_OK) {
            u->phase = BOOT_PHASE_IDLE;
            return refuse(FW_REASON_FLASH, 0, 0);
        }
    }
    ++u->programmed_words;
    if (u->flash->program(u->flash->ctx, at, &w[0], 1) != FLASH_OPS_OK) {
        u->phase = BOOT_PHASE_IDLE;
        return refuse(FW_REASON_FLASH, 0, 0);
    }
    if (boot_image_check(app_bytes(u), l->app_bytes, l->flash_base + l->app_offset, u->board, &h) != BOOT_IMAGE_OK) {
        u->phase = BOOT_PHASE_IDLE;
        return refuse(FW_REASON_CRC, 0, 0);
    }
    u->phase = BOOT_PHASE_DONE;
    return accept(h.crc & 0x7FFFFFFFu);
}
