/*
 * bxCAN acceptance filtering (stm32f4_bxcan_filter.h), from RM0090 32.7.4:
 * - a bank is 32-bit (FS1R set: one filter in mask mode, FR1 the identifier and FR2 the mask;
 *   two identifiers FR1, FR2 in list mode) or 16-bit (two mask filters, each register's low half
 *   the identifier and its high half the mask; or four identifiers, the registers' halves);
 * - the 16-bit layout is STID in 15..5, RTR in 4, IDE in 3, EXID[17:15] in 2..0;
 * - filter match indexes count the filters of every bank assigned to a FIFO (FFA1R), active or
 *   not, in bank order, each bank contributing 1, 2, 2 or 4 of them;
 * - of several filters that accept a frame, a 32-bit one beats a 16-bit one, a list one beats a
 *   mask one, then the lower filter number wins.
 *
 * SPDX-License-Identifier: GPL-2.0-or-later
 */
#include "qemu/osdep.h"
#include "stm32f4_bxcan_filter.h"

uint32_t bxcan_filter_word(uint32_t id, bool ide, bool rtr)
{
    if (ide) {
        return (id >> 18) << 21 | (id & 0x3FFFF) << 3 | 1u << 2 | (uint32_t)rtr << 1;
    }
    return (id & 0x7FF) << 21 | (uint32_t)rtr << 1;
}

/* The 16-bit view of a 32-bit word. */
static uint16_t half_of(uint32_t word)
{
    const uint32_t stid = word >> 21, exid_top = (word >> 18) & 7;
    const uint32_t rtr = (word >> 1) & 1, ide = (word >> 2) & 1;
    return stid << 5 | rtr << 4 | ide << 3 | exid_top;
}

/* Rank of a filter kind: lower is preferred. */
static int rank(bool scale32, bool list)
{
    return (scale32 ? 0 : 2) + (list ? 0 : 1);
}

BxcanMatch bxcan_filter_match(const BxcanFilters *f, uint32_t word)
{
    BxcanMatch best = { -1, 0 };
    int best_rank = 99;
    unsigned number[2] = { 0, 0 };
    unsigned banks = (f->fmr >> 8) & 0x3F;
    const uint32_t w = word & ~1u;
    const uint16_t h = half_of(word);

    if (banks > BXCAN_FILTER_BANKS) {
        banks = BXCAN_FILTER_BANKS;
    }
    for (unsigned b = 0; b < banks; ++b) {
        const bool scale32 = (f->fs1r >> b) & 1, list = (f->fm1r >> b) & 1;
        const int fifo = (f->ffa1r >> b) & 1;
        const unsigned count = scale32 ? (list ? 2 : 1) : (list ? 4 : 2);
        const uint32_t r1 = f->fr[b][0], r2 = f->fr[b][1];
        int hit = -1; /* index within the bank */

        if ((f->fa1r >> b) & 1) {
            if (scale32 && list) {
                hit = (r1 & ~1u) == w ? 0 : (r2 & ~1u) == w ? 1 : -1;
            } else if (scale32) {
                hit = ((w ^ r1) & r2 & ~1u) == 0 ? 0 : -1;
            } else if (list) {
                const uint16_t ids[4] = { r1, r1 >> 16, r2, r2 >> 16 };
                for (int i = 0; i < 4 && hit < 0; ++i) {
                    hit = ids[i] == h ? i : -1;
                }
            } else {
                const uint32_t regs[2] = { r1, r2 };
                for (int i = 0; i < 2 && hit < 0; ++i) {
                    const uint16_t id = regs[i], mask = regs[i] >> 16;
                    hit = ((h ^ id) & mask) == 0 ? i : -1;
                }
            }
        }
        if (hit >= 0) {
            const int r = rank(scale32, list);
            const unsigned fmi = number[fifo] + hit;
            /* Same rank: the lower filter number, i.e. the one found first in its FIFO. */
            if (r < best_rank) {
                best_rank = r;
                best.fifo = fifo;
                best.fmi = fmi;
            }
        }
        number[fifo] += count;
    }
    return best;
}
