/* The node filter, applied by a small model of the bxCAN filter hardware written here from the
 * reference manual (RM0090 32.7.4), to every 11-bit identifier as a standard and as an extended
 * frame, data and remote: FIFO 0 must get exactly the standard data frames whose node bits are
 * this node's or the broadcast node's, and nothing must go to FIFO 1. */
#include <setjmp.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>

#include "hal_stm32f4/bxcan_filter.h"

/* The protocol's own definitions: the filter's copies must agree with them. */
#include "fw/proto_wire.h"

_Static_assert(BXCAN_NODE_BITS == PROTO_NODE_BITS, "node bits");
_Static_assert(BXCAN_NODE_MASK == PROTO_NODE_MASK, "node mask");
_Static_assert(BXCAN_BROADCAST == PROTO_BROADCAST, "broadcast node");

/* A received frame as the filter sees it: the 32-bit form of RIxR (STID in 31:21, EXID in
 * 20:3, IDE in 2, RTR in 1). */
static uint32_t frame32(uint32_t id, bool extended, bool remote)
{
    const uint32_t base = extended ? (id & 0x1FFFFFFFu) << 3 | 1u << 2 : (id & 0x7FFu) << 21;
    return base | (remote ? 1u << 1 : 0u);
}

/* The 16-bit form: STID[10:0] in 15:5, RTR in 4, IDE in 3, EXID[17:15] in 2:0. */
static uint32_t frame16(uint32_t f32)
{
    const uint32_t stid = f32 >> 21, exid_hi = (f32 >> 18) & 0x7u;
    return stid << 5 | ((f32 >> 1) & 1u) << 4 | ((f32 >> 2) & 1u) << 3 | exid_hi;
}

static bool match_mask(uint32_t frame, uint32_t id, uint32_t mask)
{
    return ((frame ^ id) & mask) == 0;
}

/* Does bank b (configured per r) accept the frame? */
static bool bank_accepts(const bxcan_filter_regs *r, unsigned b, uint32_t f32)
{
    const bool list = (r->fm1r >> b) & 1u, wide = (r->fs1r >> b) & 1u;
    const uint32_t fr1 = r->fr1[b], fr2 = r->fr2[b];
    if (wide) { /* bit 0 of the frame word is not part of the identifier */
        const uint32_t f = f32 & ~1u;
        return list ? f == (fr1 & ~1u) || f == (fr2 & ~1u) : match_mask(f, fr1, fr2 & ~1u);
    }
    const uint32_t f = frame16(f32);
    if (list)
        return f == (fr1 & 0xFFFFu) || f == fr1 >> 16 || f == (fr2 & 0xFFFFu) || f == fr2 >> 16;
    return match_mask(f, fr1 & 0xFFFFu, fr1 >> 16) || match_mask(f, fr2 & 0xFFFFu, fr2 >> 16);
}

/* The FIFO a frame lands in (0 or 1), or -1 when every active bank rejects it. */
static int route(const bxcan_filter_regs *r, uint32_t f32)
{
    for (unsigned b = 0; b < BXCAN_CAN1_BANKS; ++b)
        if (((r->fa1r >> b) & 1u) && bank_accepts(r, b, f32))
            return (int)((r->ffa1r >> b) & 1u);
    return -1;
}

static void check_node(uint8_t node)
{
    bxcan_filter_regs r;
    assert_int_equal(bxcan_filter_for_node(node, &r), 0);
    assert_int_equal(r.fa1r >> BXCAN_CAN1_BANKS, 0); /* only CAN1's banks */
    unsigned passed = 0;
    for (uint32_t id = 0; id <= 0x7FFu; ++id) {
        const uint32_t n = id & 0xFu; /* node: the low 4 bits of function << 4 | node */
        const bool wanted = n == node || n == 0;
        for (int remote = 0; remote < 2; ++remote) {
            const int fifo = route(&r, frame32(id, false, remote));
            assert_int_equal(fifo, wanted && !remote ? 0 : -1);
            passed += fifo == 0;
            /* Extended frames: the same 11 bits as the whole identifier, as its top 11 bits
             * (what a standard-frame filter would compare), and with every low bit set. */
            const uint32_t ext[] = {id, id << 18, id << 18 | 0x3FFFFu};
            for (size_t e = 0; e < sizeof ext / sizeof *ext; ++e)
                assert_int_equal(route(&r, frame32(ext[e], true, remote)), -1);
        }
    }
    assert_int_equal(passed, 2 * 128); /* 128 functions, for the node and for node 0 */
}

static void every_node_every_identifier(void **state)
{
    (void)state;
    for (uint8_t node = 1; node <= 15; ++node)
        check_node(node);
}

/* Worked by hand for node 5: two 16-bit mask filters, mask = node bits (0xF << 5) | RTR (0x10)
 * | IDE (0x08) = 0x1F8 in the high half; identifiers 5 << 5 = 0xA0 and 0. */
static void node_5_registers(void **state)
{
    (void)state;
    bxcan_filter_regs r;
    assert_int_equal(bxcan_filter_for_node(5, &r), 0);
    assert_int_equal(r.fr1[0], 0x01F800A0u);
    assert_int_equal(r.fr2[0], 0x01F80000u);
    assert_int_equal(r.fa1r, 1u);
    assert_int_equal(r.fm1r & 1u, 0u);  /* mask mode */
    assert_int_equal(r.fs1r & 1u, 0u);  /* 16-bit scale */
    assert_int_equal(r.ffa1r & 1u, 0u); /* FIFO 0 */
}

static void rejects_non_controller_nodes(void **state)
{
    (void)state;
    bxcan_filter_regs r;
    assert_int_equal(bxcan_filter_for_node(0, &r), -1);
    assert_int_equal(bxcan_filter_for_node(16, &r), -1);
    assert_int_equal(bxcan_filter_for_node(255, &r), -1);
}

/* The model itself must be able to fail: a 16-bit filter that ignores RTR lets remote frames
 * through, a 32-bit mask filter on the node bits works as expected, list mode matches exactly. */
static void model_sanity(void **state)
{
    (void)state;
    bxcan_filter_regs r = {0};
    r.fa1r = 1u;
    r.fr1[0] = (0xFu << 5 | 1u << 3) << 16 | 3u << 5; /* node 3, IDE = 0, RTR free */
    r.fr2[0] = 0xFFFFu << 16 | 0xFFFFu;                /* matches nothing real */
    assert_int_equal(route(&r, frame32(0x123, false, true)), 0);
    assert_int_equal(route(&r, frame32(0x124, false, false)), -1);
    r.fs1r = 1u; /* 32-bit: identifier 0x7F3 exactly, data or remote, standard only */
    r.fr1[0] = 0x7F3u << 21;
    r.fr2[0] = 0x7FFu << 21 | 1u << 2;
    assert_int_equal(route(&r, frame32(0x7F3, false, true)), 0);
    assert_int_equal(route(&r, frame32(0x7F3, true, false)), -1);
    r.fm1r = 1u; /* 32-bit list: two exact frames */
    r.ffa1r = 1u;
    r.fr1[0] = frame32(0x010, false, false);
    r.fr2[0] = frame32(0x1ABCDEF, true, true);
    assert_int_equal(route(&r, frame32(0x010, false, false)), 1);
    assert_int_equal(route(&r, frame32(0x1ABCDEF, true, true)), 1);
    assert_int_equal(route(&r, frame32(0x1ABCDEF, true, false)), -1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(every_node_every_identifier),
        cmocka_unit_test(node_5_registers),
        cmocka_unit_test(rejects_non_controller_nodes),
        cmocka_unit_test(model_sanity),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
