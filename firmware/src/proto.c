#include "fw/proto.h"

#include <string.h>

static const uint8_t field_size[] = {
    [PF_U8] = 1, [PF_I8] = 1, [PF_U16] = 2, [PF_I16] = 2,
    [PF_U24] = 3, [PF_I24] = 3, [PF_U32] = 4, [PF_I32] = 4,
};

static bool field_signed(proto_field_type t)
{
    return t == PF_I8 || t == PF_I16 || t == PF_I24 || t == PF_I32;
}

proto_msg proto_find(uint8_t function, proto_direction dir)
{
    for (int i = 0; i < PM_COUNT; ++i)
        if (proto_wire[i].function == function && proto_wire[i].dir == dir)
            return (proto_msg)i;
    return PM_COUNT;
}

uint16_t proto_id(proto_msg msg, uint8_t node)
{
    return (uint16_t)((proto_wire[msg].function << PROTO_NODE_BITS) | (node & PROTO_NODE_MASK));
}

static void put(uint8_t *p, uint32_t raw, unsigned n)
{
    for (unsigned k = 0; k < n; ++k)
        p[k] = (uint8_t)(raw >> (8u * k));
}

static int64_t get(const uint8_t *p, proto_field_type t)
{
    const unsigned n = field_size[t];
    uint32_t raw = 0;
    for (unsigned k = 0; k < n; ++k)
        raw |= (uint32_t)p[k] << (8u * k);
    /* n is 1..4 (field_size covers every type); the analyzer, not reading the table, tries 0.
     * NOLINTNEXTLINE(clang-analyzer-core.UndefinedBinaryOperatorResult) */
    if (field_signed(t) && n < 4 && (raw & (1u << (8u * n - 1u))))
        raw |= ~0u << (8u * n); /* sign-extend */
    return field_signed(t) ? (int64_t)(int32_t)raw : (int64_t)raw;
}

int proto_encode(const proto_message *m, hal_can_frame *f)
{
    if ((unsigned)m->msg >= PM_COUNT || m->node > PROTO_NODE_MASK)
        return -1;
    const proto_wire_msg *d = &proto_wire[m->msg];
    for (int i = 0; i < d->nfields; ++i)
        if (m->v[i] < d->fields[i].min || m->v[i] > d->fields[i].max)
            return -1;
    hal_can_frame out;
    memset(&out, 0, sizeof out);
    out.id = proto_id(m->msg, m->node);
    out.len = d->dlc;
    for (int i = 0; i < d->nfields; ++i)
        put(&out.data[d->fields[i].offset], (uint32_t)m->v[i], field_size[d->fields[i].type]);
    *f = out;
    return 0;
}

int proto_encode_values(proto_msg msg, uint8_t node, const int32_t *values, hal_can_frame *f)
{
    if ((unsigned)msg >= PM_COUNT)
        return -1;
    proto_message m;
    memset(&m, 0, sizeof m);
    m.msg = msg;
    m.node = node;
    for (int i = 0; i < proto_wire[msg].nfields; ++i)
        /* Each caller's array holds its message's nfields; the analyzer cannot see the table's.
         * NOLINTNEXTLINE(clang-analyzer-core.uninitialized.Assign) */
        m.v[i] = values[i];
    return proto_encode(&m, f);
}

proto_error proto_decode(const hal_can_frame *f, proto_direction dir, proto_message *m)
{
    proto_error e = {FW_REASON_NONE, 0};
    const proto_msg msg = f->id <= HAL_CAN_MAX_ID ? proto_find((uint8_t)(f->id >> PROTO_NODE_BITS), dir) : PM_COUNT;
    if (msg == PM_COUNT) {
        e.reason = FW_REASON_UNKNOWN;
        return e;
    }
    const proto_wire_msg *d = &proto_wire[msg];
    if (f->len != d->dlc) {
        e.reason = FW_REASON_BAD_LENGTH;
        return e;
    }
    proto_message out;
    memset(&out, 0, sizeof out);
    out.msg = msg;
    out.node = (uint8_t)(f->id & PROTO_NODE_MASK);
    for (int i = 0; i < d->nfields; ++i) {
        const proto_wire_field *fd = &d->fields[i];
        const int64_t v = get(&f->data[fd->offset], (proto_field_type)fd->type);
        if (v < fd->min || v > fd->max) {
            e.reason = FW_REASON_RANGE;
            e.field = (uint8_t)i;
            return e;
        }
        out.v[i] = (int32_t)v;
    }
    *m = out;
    return e;
}
