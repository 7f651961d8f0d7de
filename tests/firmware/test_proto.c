/* CAN codec: byte layout against frames assembled by hand, round trips of every message,
 * and every way a frame can be malformed. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "fw/proto.h"

/* POSE_A, node 3, seq 0x12, x = -1 um, y = 1000000 um: id 0x0A3, little-endian 24-bit fields. */
static void test_hand_built_pose(void **state)
{
    (void)state;
    proto_message m = {PM_POSE_A, 3, {0x12, -1, 1000000}};
    hal_can_frame f;
    assert_int_equal(proto_encode(&m, &f), 0);
    assert_int_equal(f.id, 0x0A3);
    assert_int_equal(f.len, 7);
    const uint8_t want[7] = {0x12, 0xFF, 0xFF, 0xFF, 0x40, 0x42, 0x0F};
    assert_memory_equal(f.data, want, 7);

    proto_message back;
    const proto_error e = proto_decode(&f, PROTO_TO_CONTROLLER, &back);
    assert_int_equal(e.reason, FW_REASON_NONE);
    assert_int_equal(back.msg, PM_POSE_A);
    assert_int_equal(back.node, 3);
    assert_int_equal(back.v[1], -1);
    assert_int_equal(back.v[2], 1000000);
}

/* E-stop has the lowest identifier of all: it wins arbitration. */
static void test_estop_has_priority(void **state)
{
    (void)state;
    for (int i = 0; i < PM_COUNT; ++i)
        if (i != PM_ESTOP)
            assert_true(proto_table[i].function > proto_table[PM_ESTOP].function);
}

/* The table is consistent: unique function codes per direction, fields inside the frame and not
 * overlapping, ranges representable in their type. */
static void test_table_consistent(void **state)
{
    (void)state;
    static const int size[] = {1, 1, 2, 2, 3, 3, 4, 4};
    for (int i = 0; i < PM_COUNT; ++i) {
        const proto_def *d = &proto_table[i];
        assert_int_equal(d->msg, i);
        assert_true(d->function > 0 && d->function < 128);
        assert_true(d->dlc <= 8);
        for (int j = i + 1; j < PM_COUNT; ++j)
            assert_false(proto_table[j].function == d->function);
        uint8_t used = 0;
        for (int k = 0; k < d->nfields; ++k) {
            const proto_field *fd = &d->fields[k];
            const int n = size[fd->type];
            assert_true(fd->offset + n <= d->dlc);
            for (int b = fd->offset; b < fd->offset + n; ++b) {
                assert_false((used >> b) & 1u);
                used |= (uint8_t)(1u << b);
            }
            assert_true(fd->min <= fd->max);
            const int signed_type = fd->type == PF_I8 || fd->type == PF_I16 || fd->type == PF_I24 || fd->type == PF_I32;
            if (n < 4) {
                const int64_t lo = signed_type ? -(1LL << (8 * n - 1)) : 0;
                const int64_t hi = signed_type ? (1LL << (8 * n - 1)) - 1 : (1LL << (8 * n)) - 1;
                assert_true(fd->min >= lo && fd->max <= hi);
            } else if (!signed_type) {
                assert_true(fd->min >= 0);
            }
        }
    }
}

/* The codec's wire table and the host's documentation table, both made from fw/proto_messages.def,
 * say the same of every message: function code, direction, length, and each field's type, first
 * byte and range; a field is a sequence number exactly where it is named seq.  The lookups agree. */
static void test_wire_table_is_the_documented_one(void **state)
{
    (void)state;
    for (int i = 0; i < PM_COUNT; ++i) {
        const proto_wire_msg *w = &proto_wire[i];
        const proto_def *d = &proto_table[i];
        assert_int_equal(w->function, d->function);
        assert_int_equal(w->dir, d->dir);
        assert_int_equal(w->dlc, d->dlc);
        assert_int_equal(w->nfields, d->nfields);
        assert_true(w->nfields >= 1 && w->nfields <= PROTO_MAX_FIELDS);
        for (int k = 0; k < d->nfields; ++k) {
            assert_int_equal(w->fields[k].type, d->fields[k].type);
            assert_int_equal(w->fields[k].offset, d->fields[k].offset);
            assert_int_equal(w->fields[k].min, d->fields[k].min);
            assert_int_equal(w->fields[k].max, d->fields[k].max);
            assert_int_equal(w->fields[k].seq, strcmp(d->fields[k].name, "seq") == 0);
        }
        for (int dir = PROTO_TO_CONTROLLER; dir <= PROTO_TO_HOST; ++dir) {
            const proto_msg m = proto_find(d->function, (proto_direction)dir);
            const proto_def *l = proto_lookup(d->function, (proto_direction)dir);
            assert_int_equal(m, dir == (int)d->dir ? i : PM_COUNT);
            assert_ptr_equal(l, m == PM_COUNT ? NULL : &proto_table[m]);
        }
    }
    assert_int_equal(proto_find(0x7F, PROTO_TO_CONTROLLER), PM_COUNT);
    assert_null(proto_lookup(0x7F, PROTO_TO_CONTROLLER));
}

static int32_t random_in(int32_t lo, int32_t hi)
{
    const uint64_t span = (uint64_t)((int64_t)hi - lo) + 1u;
    const uint64_t r = ((uint64_t)rand() << 31 ^ (uint64_t)rand()) % span;
    return (int32_t)((int64_t)lo + (int64_t)r);
}

static void test_round_trip_all(void **state)
{
    (void)state;
    srand(11);
    for (int rep = 0; rep < 2000; ++rep) {
        for (int i = 0; i < PM_COUNT; ++i) {
            const proto_def *d = &proto_table[i];
            proto_message m = {(proto_msg)i, (uint8_t)(1 + rand() % 15), {0}};
            for (int k = 0; k < d->nfields; ++k) {
                const int pick = rand() % 4; /* the bounds themselves, often */
                m.v[k] = pick == 0 ? d->fields[k].min : pick == 1 ? d->fields[k].max
                                                                  : random_in(d->fields[k].min, d->fields[k].max);
            }
            hal_can_frame f;
            assert_int_equal(proto_encode(&m, &f), 0);
            proto_message back;
            const proto_error e = proto_decode(&f, d->dir, &back);
            assert_int_equal(e.reason, FW_REASON_NONE);
            assert_int_equal(back.msg, m.msg);
            assert_int_equal(back.node, m.node);
            for (int k = 0; k < d->nfields; ++k)
                assert_int_equal(back.v[k], m.v[k]);
        }
    }
}

static void test_rejects(void **state)
{
    (void)state;
    proto_message m = {PM_MOVE_COMMIT, 1, {5, 0, 1000}};
    hal_can_frame f;
    assert_int_equal(proto_encode(&m, &f), 0);
    proto_message out;

    /* Every wrong length. */
    for (uint8_t len = 0; len <= 8; ++len) {
        hal_can_frame g = f;
        g.len = len;
        const proto_error e = proto_decode(&g, PROTO_TO_CONTROLLER, &out);
        assert_int_equal(e.reason, len == f.len ? FW_REASON_NONE : FW_REASON_BAD_LENGTH);
    }
    /* Unknown function codes, and a host-bound message sent to a controller. */
    hal_can_frame g = f;
    g.id = (uint16_t)(0x7F << 4 | 1);
    assert_int_equal(proto_decode(&g, PROTO_TO_CONTROLLER, &out).reason, FW_REASON_UNKNOWN);
    g.id = (uint16_t)(0x20 << 4 | 1); /* STATUS */
    g.len = 8;
    assert_int_equal(proto_decode(&g, PROTO_TO_CONTROLLER, &out).reason, FW_REASON_UNKNOWN);
    g.id = 0x800; /* not an 11-bit identifier */
    assert_int_equal(proto_decode(&g, PROTO_TO_CONTROLLER, &out).reason, FW_REASON_UNKNOWN);

    /* Out of range: kind 2 (field 1), duration 0 (field 2). */
    g = f;
    g.data[1] = 2;
    proto_error e = proto_decode(&g, PROTO_TO_CONTROLLER, &out);
    assert_int_equal(e.reason, FW_REASON_RANGE);
    assert_int_equal(e.field, 1);
    g = f;
    memset(&g.data[2], 0, 4);
    e = proto_decode(&g, PROTO_TO_CONTROLLER, &out);
    assert_int_equal(e.reason, FW_REASON_RANGE);
    assert_int_equal(e.field, 2);
    /* A 24-bit coordinate past +-4 m. */
    proto_message p = {PM_POSE_B, 1, {1, 0, 0}};
    assert_int_equal(proto_encode(&p, &g), 0);
    g.data[1] = 0x01;
    g.data[2] = 0x09;
    g.data[3] = 0x3D; /* 0x3D0901 = 4000001 */
    e = proto_decode(&g, PROTO_TO_CONTROLLER, &out);
    assert_int_equal(e.reason, FW_REASON_RANGE);
    assert_int_equal(e.field, 1);

    /* The encoder refuses what the decoder would. */
    p.v[1] = 4000001;
    assert_int_equal(proto_encode(&p, &g), -1);
    p.v[1] = 0;
    p.node = 16;
    assert_int_equal(proto_encode(&p, &g), -1);
}

static void test_enum_names(void **state)
{
    (void)state;
    assert_string_equal(proto_enum_name(proto_state_names, FW_STATE_ESTOP), "estop");
    assert_string_equal(proto_enum_name(proto_reason_names, FW_REASON_KINEMATICS), "kinematics");
    assert_string_equal(proto_enum_name(proto_kin_status_names, 2), "unreachable");
    assert_string_equal(proto_enum_name(proto_state_names, 99), "?");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hand_built_pose), cmocka_unit_test(test_estop_has_priority),
        cmocka_unit_test(test_table_consistent), cmocka_unit_test(test_round_trip_all),
        cmocka_unit_test(test_rejects),          cmocka_unit_test(test_enum_names),
        cmocka_unit_test(test_wire_table_is_the_documented_one),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
