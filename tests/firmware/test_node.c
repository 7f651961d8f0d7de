/* The node id and the ENABLE level as parameters (docs/protocol.md, "Parameters"; docs/board.md,
 * "Node id and ENABLE level"): `node` (id 35) and `enable_level` (id 36), appended after traj_lead
 * (34).  A PARAM_SET of node changes the stored value only: PARAM_GET shows it, the controller
 * keeps answering on the id it started with; after PARAM_SAVE, a controller started with node 0
 * in its configuration (the board, tse-sim without --node) answers on the saved id, and a
 * configured id overrides it.  The frames are written and read byte by byte as docs/protocol.md
 * lays them out (id = function << 4 | node; little-endian fields), not through the codec. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "harness.h"

#define P_NODE 35u
#define P_ENABLE_LEVEL 36u
#define F_REJECT 0x03u
#define F_ACK 0x04u
#define F_PARAM_GET 0x0Fu
#define F_PARAM_SET 0x10u
#define F_PARAM_SAVE 0x11u
#define F_INFO_GET 0x12u
#define F_PARAM_VALUE 0x27u
#define F_INFO 0x29u
#define REASON_PARAM_RANGE 11u /* docs/protocol.md, "reject reason" */

static uint16_t id_of(unsigned function, unsigned node)
{
    return (uint16_t)(function << 4 | node);
}

/* The frames c sent from index `from` with identifier id. */
static unsigned sent_with(const fake_hal *f, unsigned from, uint16_t id, const hal_can_frame **last)
{
    unsigned n = 0;
    for (unsigned i = from; i < f->tx_count; ++i)
        if (f->tx[i].id == id) {
            ++n;
            *last = &f->tx[i];
        }
    return n;
}

static void param_set(fake_hal *f, fw_controller *c, unsigned node, unsigned param, int32_t value)
{
    const uint32_t v = (uint32_t)value;
    const uint8_t d[6] = {(uint8_t)param, (uint8_t)(param >> 8), (uint8_t)v, (uint8_t)(v >> 8), (uint8_t)(v >> 16),
                          (uint8_t)(v >> 24)};
    fake_send(f, id_of(F_PARAM_SET, node), 6, d);
    fw_poll(c);
}

/* PARAM_GET of param at node: the value its PARAM_VALUE carries. */
static int32_t param_get(fake_hal *f, fw_controller *c, unsigned node, unsigned param)
{
    const unsigned from = f->tx_count;
    const uint8_t d[2] = {(uint8_t)param, (uint8_t)(param >> 8)};
    fake_send(f, id_of(F_PARAM_GET, node), 2, d);
    fw_poll(c);
    const hal_can_frame *pv = NULL;
    assert_int_equal(sent_with(f, from, id_of(F_PARAM_VALUE, node), &pv), 1);
    assert_int_equal(pv->data[0] | pv->data[1] << 8, param);
    return (int32_t)((uint32_t)pv->data[2] | (uint32_t)pv->data[3] << 8 | (uint32_t)pv->data[4] << 16 |
                     (uint32_t)pv->data[5] << 24);
}

/* Whether an INFO_GET page 0 addressed to node is answered (ACK and INFO from that node). */
static bool answers_at(fake_hal *f, fw_controller *c, unsigned node)
{
    const unsigned from = f->tx_count;
    const uint8_t page = 0;
    fake_send(f, id_of(F_INFO_GET, node), 1, &page);
    fw_poll(c);
    const hal_can_frame *x = NULL;
    const bool ack = sent_with(f, from, id_of(F_ACK, node), &x) == 1;
    const bool info = sent_with(f, from, id_of(F_INFO, node), &x) == 1;
    return ack && info;
}

static void save(fake_hal *f, fw_controller *c, unsigned node)
{
    const unsigned from = f->tx_count;
    const uint8_t magic[4] = {'S', 'A', 'V', 'E'};
    fake_send(f, id_of(F_PARAM_SAVE, node), 4, magic);
    fw_poll(c);
    const hal_can_frame *ack = NULL;
    assert_int_equal(sent_with(f, from, id_of(F_ACK, node), &ack), 1);
    assert_int_equal(ack->data[0], F_PARAM_SAVE);
}

/* A power cycle keeping what storage holds, the controller configured with `node`. */
static fw_controller *power_cycle(uint8_t node)
{
    static fw_controller_mem mem;
    uint8_t kept[sizeof F.storage];
    const int len = F.storage_len;
    memcpy(kept, F.storage, sizeof kept);
    fw_hal hal;
    fake_hal_init(&F, &hal);
    memcpy(F.storage, kept, sizeof kept);
    F.storage_len = len;
    const fw_config cfg = {node, 1000, 100000, NULL, NULL, NULL};
    fw_controller *c = fw_init(&mem, &hal, &cfg);
    assert_non_null(c);
    return c;
}

static void a_set_node_is_stored_and_taken_at_the_next_start(void **state)
{
    (void)state;
    start(); /* node 1, as configured */
    const unsigned from = F.tx_count;
    param_set(&F, C, 1, P_NODE, 5);
    const hal_can_frame *x = NULL;
    assert_int_equal(sent_with(&F, from, id_of(F_ACK, 1), &x), 1);
    assert_int_equal(sent_with(&F, from, id_of(F_PARAM_VALUE, 1), &x), 1); /* from node 1 still */
    assert_int_equal(x->data[2], 5);
    /* PARAM_GET shows the stored value; the controller answers on the id it started with. */
    assert_int_equal(param_get(&F, C, 1, P_NODE), 5);
    assert_true(answers_at(&F, C, 1));
    assert_false(answers_at(&F, C, 5));
    assert_int_equal(fw_config_of(C)->node, 1);
    save(&F, C, 1);
    /* Started with node 0 (the board, tse-sim without --node): the saved id. */
    fw_controller *c = power_cycle(0);
    assert_int_equal(fw_config_of(c)->node, 5);
    assert_true(answers_at(&F, c, 5));
    assert_false(answers_at(&F, c, 1));
    assert_int_equal(param_get(&F, c, 5, P_NODE), 5);
    /* A configured id (tse-sim --node 3) overrides the parameter, which stays as saved. */
    c = power_cycle(3);
    assert_true(answers_at(&F, c, 3));
    assert_false(answers_at(&F, c, 5));
    assert_int_equal(param_get(&F, c, 3, P_NODE), 5);
}

static void unsaved_node_is_lost_at_restart(void **state)
{
    (void)state;
    start();
    param_set(&F, C, 1, P_NODE, 9);
    fw_controller *c = power_cycle(0);
    assert_int_equal(fw_config_of(c)->node, 1); /* the default: nothing was saved */
    assert_true(answers_at(&F, c, 1));
    assert_false(answers_at(&F, c, 9));
}

/* node 1..15 and enable_level 0..2; outside, REJECT param_range naming the parameter, nothing
 * changed. */
static void out_of_range_is_refused(void **state)
{
    (void)state;
    start();
    static const struct {
        unsigned param;
        int32_t value;
    } bad[] = {{P_NODE, 0}, {P_NODE, 16}, {P_NODE, -1}, {P_ENABLE_LEVEL, 3}, {P_ENABLE_LEVEL, -1}};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        const unsigned from = F.tx_count;
        param_set(&F, C, 1, bad[i].param, bad[i].value);
        const hal_can_frame *rej = NULL;
        if (sent_with(&F, from, id_of(F_REJECT, 1), &rej) != 1)
            fail_msg("parameter %u = %d not refused", bad[i].param, (int)bad[i].value);
        assert_int_equal(rej->data[0], F_PARAM_SET);
        assert_int_equal(rej->data[2], REASON_PARAM_RANGE);
        assert_int_equal(rej->data[5], bad[i].param);
    }
    assert_int_equal(param_get(&F, C, 1, P_NODE), 1);
    assert_int_equal(param_get(&F, C, 1, P_ENABLE_LEVEL), 0); /* default: the board's own level */
    for (int32_t level = 0; level <= 2; ++level) {
        param_set(&F, C, 1, P_ENABLE_LEVEL, level);
        assert_int_equal(param_get(&F, C, 1, P_ENABLE_LEVEL), level);
    }
    param_set(&F, C, 1, P_NODE, 15);
    assert_int_equal(param_get(&F, C, 1, P_NODE), 15);
}

/* What a platform reads before fw_init (the board's ENABLE level): the stored set, or the
 * defaults. */
static void the_stored_set_is_read_before_start(void **state)
{
    (void)state;
    start();
    fw_hal hal;
    fake_hal_init(&F, &hal); /* storage empty */
    fw_param_set s;
    fw_params_stored(&hal.storage, &s);
    assert_int_equal(s.v[P_ENABLE_LEVEL], 0);
    assert_int_equal(s.v[P_NODE], 1);
    C = power_cycle(1);
    param_set(&F, C, 1, P_ENABLE_LEVEL, 2);
    save(&F, C, 1);
    fw_params_stored(&hal.storage, &s);
    assert_int_equal(s.v[P_ENABLE_LEVEL], 2);
    F.storage[10] ^= 0x40u; /* a corrupt record: the defaults */
    fw_params_stored(&hal.storage, &s);
    assert_int_equal(s.v[P_ENABLE_LEVEL], 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(a_set_node_is_stored_and_taken_at_the_next_start),
        cmocka_unit_test(unsaved_node_is_lost_at_restart),
        cmocka_unit_test(out_of_range_is_refused),
        cmocka_unit_test(the_stored_set_is_read_before_start),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
