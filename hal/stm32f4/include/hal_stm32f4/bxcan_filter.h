/* The acceptance filter of one controller node: the register values that make the bxCAN's
 * FIFO 0 receive exactly the standard (11-bit) data frames addressed to `node` or to the
 * broadcast node 0, and nothing else (extended and remote frames are rejected by the hardware,
 * not by software).
 *
 * Identifiers are function << 4 | node (firmware/include/fw/proto_wire.h: PROTO_NODE_BITS,
 * PROTO_NODE_MASK, PROTO_BROADCAST; this layer cannot include the firmware, so the values are
 * repeated below and a test checks that they agree).
 *
 * One bank, in 16-bit mask mode: two filters, "node bits == node" and "node bits == 0", each
 * also requiring RTR = 0 and IDE = 0.  (A single mask cannot do it: node and 0 differ in the
 * bits set in node, so masking them out would let other nodes through.)
 * Plain arithmetic: no register access; bxcan.c writes the result. */
#ifndef TSE_BXCAN_FILTER_H
#define TSE_BXCAN_FILTER_H

#include <stdint.h>

#define BXCAN_NODE_BITS 4u
#define BXCAN_NODE_MASK 0x0Fu
#define BXCAN_BROADCAST 0u

/* Banks 0..13 belong to CAN1 while FMR.CAN2SB keeps its reset value 14; this driver touches
 * only those. */
#define BXCAN_CAN1_BANKS 14u

typedef struct {
    /* Bit n of each describes bank n (0..13), as in FM1R, FS1R, FFA1R and FA1R. */
    uint32_t fm1r;  /* set: identifier-list mode; clear: mask mode */
    uint32_t fs1r;  /* set: one 32-bit filter; clear: two 16-bit filters */
    uint32_t ffa1r; /* set: FIFO 1; clear: FIFO 0 */
    uint32_t fa1r;  /* set: active */
    uint32_t fr1[BXCAN_CAN1_BANKS], fr2[BXCAN_CAN1_BANKS];
} bxcan_filter_regs;

/* Fills *out for a controller with node id 1..15.  Returns 0, or -1 for another node (0 is the
 * broadcast address, not a controller). */
int bxcan_filter_for_node(uint8_t node, bxcan_filter_regs *out);

#endif
