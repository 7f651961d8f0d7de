#include "boot_fixture.h"

#include <string.h>

#include "boot/image.h"

uint32_t fx_crc32(const uint8_t *p, uint32_t n)
{
    uint32_t c = 0xFFFFFFFFu;
    for (uint32_t i = 0; i < n; ++i) {
        c ^= p[i];
        for (int k = 0; k < 8; ++k)
            c = (c & 1u) ? (c >> 1) ^ 0xEDB88320u : c >> 1;
    }
    return ~c;
}

static void put32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
    p[2] = (uint8_t)(v >> 16);
    p[3] = (uint8_t)(v >> 24);
}

void fx_image(uint8_t *img, uint32_t length, uint32_t board, uint32_t version, uint32_t seed)
{
    uint32_t x = seed ? seed : 1u;
    for (uint32_t i = 0; i < length; ++i) {
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        /* Some runs of erased words, as an image's padding has: they are not programmed. */
        img[i] = (i / 64u) % 7u == 3u ? 0xFF : (uint8_t)x;
    }
    put32(img, 0x20020000u);                        /* initial stack pointer */
    put32(img + 4, (FX_APP_START + 0x400u) | 1u);   /* reset handler, Thumb, after the header */
    /* The header, as docs/protocol.md lays it out: words at 0x200. */
    uint8_t *h = img + 0x200;
    memset(h, 0, 48);
    put32(h + 0, 0x49455354u);
    put32(h + 4, 1);
    put32(h + 8, board);
    put32(h + 12, version);
    put32(h + 16, length);
    memcpy(h + 24, FX_BOARD_NAME, strlen(FX_BOARD_NAME));
    /* CRC over [0, length) without the crc word at 0x214: the bytes before it, then after it. */
    static uint8_t scratch[FX_IMAGE_MAX];
    memcpy(scratch, img, 0x214);
    memcpy(scratch + 0x214, img + 0x218, length - 0x218);
    put32(h + 20, fx_crc32(scratch, length - 4u));
}

void fx_flash_init(sim_flash *f, uint32_t seed)
{
    static const uint32_t sectors[FX_NSECTORS] = {0x4000, 0x4000, 0x4000, 0x4000, 0x10000, 0x20000};
    sim_flash_init_sectors(f, sectors, FX_NSECTORS, seed);
    for (uint32_t i = 0; i < 0x4000u / 4u; ++i) {
        f->words[i] = 0xB0071000u + i;
        f->state[i] = SIM_WORD_PROGRAMMED;
    }
}

bool fx_boot_intact(const sim_flash *f)
{
    for (uint32_t i = 0; i < 0x4000u / 4u; ++i)
        if (f->words[i] != 0xB0071000u + i)
            return false;
    return f->erases[0] == 0;
}

void fx_flash_install(sim_flash *f, const uint8_t *img, uint32_t length)
{
    memcpy((uint8_t *)f->words + FX_APP_OFFSET, img, length);
    for (uint32_t i = 0; i < length / 4u; ++i)
        f->state[FX_APP_OFFSET / 4u + i] = SIM_WORD_PROGRAMMED;
}

boot_verdict fx_block(boot_update *u, const uint8_t *img, uint32_t b, uint32_t frames, uint32_t crc, bool *answered)
{
    boot_verdict v, dropped;
    uint8_t dropped_seq, seq;
    *answered = false;
    (void)boot_update_write(u, (uint8_t)b, b, frames, crc, &v, &dropped, &dropped_seq);
    if (v.reason != FW_REASON_NONE) {
        *answered = true;
        return v;
    }
    for (uint32_t k = 0; k < frames; ++k) {
        uint8_t d[8];
        memset(d, 0xFF, sizeof d);
        const uint32_t off = b * BOOT_BLOCK_BYTES + 8u * k;
        memcpy(d, img + off, 8); /* the fixture's buffers run past every image's end */
        if (boot_update_data(u, d, &v, &seq)) {
            *answered = true;
            return v;
        }
    }
    return v;
}

fx_run fx_send(boot_update *u, const uint8_t *img, uint32_t length)
{
    fx_run r;
    memset(&r, 0, sizeof r);
    r.verify = FW_REASON_STATE;
    r.erase = boot_update_erase(u, length).reason;
    if (r.erase != FW_REASON_NONE)
        return r;
    const uint32_t blocks = (length + BOOT_BLOCK_BYTES - 1u) / BOOT_BLOCK_BYTES;
    for (uint32_t b = 0; b < blocks; ++b) {
        const uint32_t off = b * BOOT_BLOCK_BYTES;
        const uint32_t bytes = length - off < BOOT_BLOCK_BYTES ? length - off : BOOT_BLOCK_BYTES;
        bool answered;
        const boot_verdict v = fx_block(u, img, b, (bytes + 7u) / 8u, fx_crc32(img + off, bytes), &answered);
        if (!answered || v.reason != FW_REASON_NONE) {
            r.first_block_refusal = answered ? v.reason : FW_REASON_UNKNOWN;
            r.refused_block = b;
            return r;
        }
        ++r.blocks_acked;
    }
    r.verify = boot_update_verify(u).reason;
    return r;
}
