/* The simulated NOR flash of sim_flash.h. */
#include "sim_flash.h"

#include <string.h>

static uint32_t next_random(sim_flash *f)
{
    /* xorshift32: enough to scatter torn bits; the seed must not be 0. */
    uint32_t x = f->rng;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    f->rng = x;
    return x;
}

void sim_flash_init(sim_flash *f, uint32_t sector_bytes, uint32_t seed)
{
    memset(f, 0, sizeof *f);
    if (sector_bytes > SIM_FLASH_MAX_SECTOR_BYTES)
        sector_bytes = SIM_FLASH_MAX_SECTOR_BYTES;
    f->sector_bytes = sector_bytes & ~3u;
    f->nsectors = 2;
    f->sector_len[0] = f->sector_len[1] = f->sector_bytes;
    f->sector_off[1] = f->sector_bytes;
    f->total_bytes = 2u * f->sector_bytes;
    f->rng = seed ? seed : 0x9E3779B9u;
    memset(f->words, 0xFF, sizeof f->words);
    /* state[] is all SIM_WORD_ERASED (0) from the memset above */
}

int sim_flash_init_sectors(sim_flash *f, const uint32_t *bytes, uint32_t nsectors, uint32_t seed)
{
    sim_flash_init(f, 0, seed);
    if (nsectors == 0 || nsectors > SIM_FLASH_MAX_SECTORS)
        return -1;
    uint32_t at = 0;
    for (uint32_t k = 0; k < nsectors; ++k) {
        if (bytes[k] % 4u != 0 || bytes[k] > 4u * SIM_FLASH_MAX_WORDS - at)
            return -1;
        f->sector_off[k] = at;
        f->sector_len[k] = bytes[k];
        at += bytes[k];
    }
    f->nsectors = nsectors;
    f->sector_bytes = bytes[0];
    f->total_bytes = at;
    return 0;
}

/* Counts one write operation; true if the power goes during it. */
static bool power_cut_now(sim_flash *f)
{
    ++f->ops;
    if (f->cut_at != 0 && f->ops == f->cut_at) {
        f->dead = true;
        f->cut_happened = true;
        return true;
    }
    return false;
}

static int sim_erase(void *ctx, uint32_t sector)
{
    sim_flash *f = ctx;
    if (sector >= f->nsectors)
        return FLASH_OPS_EARG;
    if (f->dead)
        return FLASH_OPS_EFAIL;
    const uint32_t n = f->sector_len[sector] / 4u;
    uint32_t *w = &f->words[f->sector_off[sector] / 4u];
    uint8_t *st = &f->state[f->sector_off[sector] / 4u];
    if (power_cut_now(f)) {
        f->cut_in_erase = true;
        /* How far the erase got: a threshold on a random draw per word, sometimes nothing,
         * sometimes everything (a sector that reads blank but was never fully erased). */
        const uint32_t kind = next_random(f) % 4u;
        const uint32_t threshold = kind == 0 ? 0u : kind == 1 ? UINT32_MAX : next_random(f);
        for (uint32_t i = 0; i < n; ++i) {
            const uint32_t draw = next_random(f);
            if (kind == 1 || draw < threshold)
                w[i] = 0xFFFFFFFFu;
            else if (kind > 1 && draw % 8u == 0)
                w[i] |= next_random(f); /* partly erased: some bits back to 1 */
            st[i] = SIM_WORD_UNSETTLED;
        }
        return FLASH_OPS_EFAIL;
    }
    for (uint32_t i = 0; i < n; ++i) {
        w[i] = 0xFFFFFFFFu;
        st[i] = SIM_WORD_ERASED;
    }
    ++f->erases[sector];
    return FLASH_OPS_OK;
}

static int sim_program(void *ctx, uint32_t offset, const uint32_t *words, uint32_t n)
{
    sim_flash *f = ctx;
    const uint32_t total = f->total_bytes / 4u;
    if (offset % 4u != 0 || offset / 4u > total || n > total - offset / 4u)
        return FLASH_OPS_EARG;
    for (uint32_t k = 0; k < n; ++k) {
        if (f->dead)
            return FLASH_OPS_EFAIL;
        const uint32_t i = offset / 4u + k;
        const uint32_t clear = f->words[i] & ~words[k]; /* bits this program turns to 0 */
        if (f->state[i] != SIM_WORD_ERASED || (words[k] & ~f->words[i]) != 0) {
            ++f->illegal; /* refused before it starts: not a write, no power cut here */
            return FLASH_OPS_EFAIL;
        }
        if (power_cut_now(f)) {
            f->cut_word = i;
            const uint32_t kind = next_random(f) % 4u;
            const uint32_t torn = kind == 0 ? 0u : kind == 1 ? clear : clear & next_random(f);
            f->words[i] &= ~torn;
            f->state[i] = SIM_WORD_PROGRAMMED;
            return FLASH_OPS_EFAIL;
        }
        f->words[i] &= words[k];
        f->state[i] = SIM_WORD_PROGRAMMED;
        ++f->programs;
    }
    return FLASH_OPS_OK;
}

flash_ops sim_flash_ops(sim_flash *f)
{
    return (flash_ops){f, f->words, f->sector_bytes, sim_erase, sim_program};
}

void sim_flash_cut_after(sim_flash *f, uint64_t n)
{
    f->cut_at = n ? f->ops + n : 0;
    f->cut_happened = false;
    f->cut_in_erase = false;
}

void sim_flash_reboot(sim_flash *f)
{
    f->dead = false;
    f->cut_at = 0;
}

void sim_flash_poke(sim_flash *f, uint32_t byte_offset, uint8_t value)
{
    if (byte_offset < f->total_bytes)
        ((uint8_t *)f->words)[byte_offset] = value;
}
