/*
 * bxCAN acceptance filtering (RM0090 32.7.4): which receive FIFO, if any, takes a frame, and
 * under which filter match index.  Plain functions over the filter registers.
 *
 * SPDX-License-Identifier: GPL-2.0-or-later
 */
#ifndef STM32F4_BXCAN_FILTER_H
#define STM32F4_BXCAN_FILTER_H

#include <stdbool.h>
#include <stdint.h>

#define BXCAN_FILTER_BANKS 28

typedef struct {
    uint32_t fmr, fm1r, fs1r, ffa1r, fa1r;
    uint32_t fr[BXCAN_FILTER_BANKS][2];
} BxcanFilters;

typedef struct {
    int fifo;     /* 0 or 1; -1: no filter accepts the frame */
    unsigned fmi; /* filter match index (RDTxR.FMI) */
} BxcanMatch;

/* The frame's identifier as a 32-bit filter register lays it out: STID in 31..21, EXID in
 * 20..3, IDE in 2, RTR in 1 (the RIxR layout). */
uint32_t bxcan_filter_word(uint32_t id, bool ide, bool rtr);

/* The best filter among CAN1's banks (0 .. CAN2SB-1) that accepts `word` (RM0090's priority:
 * 32-bit before 16-bit, list before mask, then the lower filter number). */
BxcanMatch bxcan_filter_match(const BxcanFilters *f, uint32_t word);

#endif
