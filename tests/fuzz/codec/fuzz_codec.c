/* The frame codec on any input.
 *
 * Input byte 0 picks what the rest is:
 *  - even: a frame (identifier 2 bytes little-endian, length, 8 data bytes) to decode in the
 *    direction of bit 1.  A frame that decodes must be exactly what the table says, field by field,
 *    read back from its bytes here (little-endian, two's complement of the field's width), and
 *    encoding the message must give the same identifier, length and field bytes.  A frame that is
 *    refused must be refused for the reason its identifier, length or fields give.
 *  - odd: a message (table index, node, seven 32-bit values) to encode.  It must be encoded exactly
 *    when the node fits and every value is in its field's range, and decode back to itself. */
#include <string.h>

#include "fuzz_target.h"
#include "wire_ref.h"
#include "fw/proto.h"

static void decode_case(const uint8_t *p, size_t n)
{
    hal_can_frame f;
    memset(&f, 0, sizeof f);
    uint8_t in[12] = {0};
    memcpy(in, p, n < sizeof in ? n : sizeof in);
    const proto_direction dir = (in[0] & 2) ? PROTO_TO_HOST : PROTO_TO_CONTROLLER;
    f.id = (uint16_t)(in[1] | in[2] << 8);
    f.len = in[3];
    memcpy(f.data, &in[4], 8);

    proto_message m;
    memset(&m, 0xA5, sizeof m);
    const proto_message untouched = m;
    const proto_error e = proto_decode(&f, dir, &m);

    const proto_def *d = f.id <= 0x7FF ? wire_ref_entry((uint8_t)(f.id >> 4), dir) : NULL;
    if (d == NULL) {
        FUZZ_CHECK(e.reason == FW_REASON_UNKNOWN);
    } else if (f.len != d->dlc) {
        FUZZ_CHECK(e.reason == FW_REASON_BAD_LENGTH);
    } else {
        int bad = -1;
        for (int i = 0; i < d->nfields && bad < 0; ++i) {
            const int64_t v = wire_ref_field(f.data, &d->fields[i]);
            if (v < d->fields[i].min || v > d->fields[i].max)
                bad = i;
        }
        if (bad >= 0) {
            FUZZ_CHECK(e.reason == FW_REASON_RANGE && e.field == bad);
        } else {
            FUZZ_CHECK(e.reason == FW_REASON_NONE);
            FUZZ_CHECK(m.msg == d->msg && m.node == (f.id & 0xF));
            for (int i = 0; i < d->nfields; ++i)
                FUZZ_CHECK(m.v[i] == wire_ref_field(f.data, &d->fields[i]));
            hal_can_frame g;
            FUZZ_CHECK(proto_encode(&m, &g) == 0);
            FUZZ_CHECK(g.id == f.id && g.len == f.len);
            for (int i = 0; i < d->nfields; ++i)
                FUZZ_CHECK(wire_ref_field(g.data, &d->fields[i]) == m.v[i]);
            return;
        }
    }
    /* A refused frame leaves the message alone. */
    FUZZ_CHECK(memcmp(&m, &untouched, sizeof m) == 0);
}

static void encode_case(const uint8_t *p, size_t n)
{
    uint8_t in[2 + 4 * PROTO_MAX_FIELDS] = {0};
    memcpy(in, p, n < sizeof in ? n : sizeof in);
    proto_message m;
    memset(&m, 0, sizeof m);
    m.msg = (proto_msg)(in[0] % (PM_COUNT + 1)); /* PM_COUNT itself: not a message */
    m.node = in[1] % 20;
    for (int i = 0; i < PROTO_MAX_FIELDS; ++i) {
        uint32_t raw;
        memcpy(&raw, &in[2 + 4 * i], 4);
        m.v[i] = (int32_t)raw;
    }
    if (m.msg < PM_COUNT) {
        /* Values near the limits are the interesting ones: fold the raw word onto the range. */
        const proto_def *d = &proto_table[m.msg];
        for (int i = 0; i < d->nfields; ++i)
            if (in[2 + 4 * i] & 1) {
                const int64_t span = (int64_t)d->fields[i].max - d->fields[i].min + 3;
                int64_t v = (int64_t)d->fields[i].min - 1 + (int64_t)((uint32_t)m.v[i] >> 1) % span;
                v = v < INT32_MIN ? INT32_MIN : v > INT32_MAX ? INT32_MAX : v;
                m.v[i] = (int32_t)v;
            }
    }
    hal_can_frame f;
    memset(&f, 0x5A, sizeof f);
    const hal_can_frame before = f;
    const int rc = proto_encode(&m, &f);

    int ok = m.msg < PM_COUNT && m.node <= 15;
    if (ok)
        for (int i = 0; i < proto_table[m.msg].nfields; ++i)
            ok &= m.v[i] >= proto_table[m.msg].fields[i].min && m.v[i] <= proto_table[m.msg].fields[i].max;
    if (!ok) {
        FUZZ_CHECK(rc == -1);
        FUZZ_CHECK(memcmp(&f, &before, sizeof f) == 0);
        return;
    }
    FUZZ_CHECK(rc == 0);
    const proto_def *d = &proto_table[m.msg];
    FUZZ_CHECK(f.id == ((unsigned)d->function << 4 | m.node) && f.len == d->dlc);
    proto_message back;
    const proto_error e = proto_decode(&f, d->dir, &back);
    FUZZ_CHECK(e.reason == FW_REASON_NONE);
    FUZZ_CHECK(back.msg == m.msg && back.node == m.node);
    for (int i = 0; i < d->nfields; ++i)
        FUZZ_CHECK(back.v[i] == m.v[i]);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size == 0)
        return 0;
    if (data[0] & 1)
        encode_case(data + 1, size - 1);
    else
        decode_case(data, size);
    return 0;
}
