#include "boot/bus.h"

#include "boot/decide.h"
#include "fw/proto.h"

void boot_bus_init(boot_bus *b, const boot_layout *layout, const flash_ops *flash, uint32_t board, uint8_t node,
                   hal_can can)
{
    boot_update_init(&b->up, layout, flash, board);
    b->can = can;
    b->node = node;
    b->start = false;
    b->sent_lost = 0;
}

static void send(boot_bus *b, proto_msg m, const int32_t *v)
{
    hal_can_frame f;
    if (proto_encode_values(m, b->node, v, &f) != 0 || b->can.send(b->can.ctx, &f) != 0)
        ++b->sent_lost;
}

static void answer(boot_bus *b, uint8_t function, uint8_t seq, const boot_verdict *v)
{
    if (v->reason == FW_REASON_NONE) {
        const int32_t a[5] = {function, seq, 0, 0, (int32_t)(v->detail > INT32_MAX ? INT32_MAX : v->detail)};
        send(b, PM_ACK, a);
    } else {
        const int32_t r[7] = {function, seq, v->reason, 0, 0, v->field, v->where};
        send(b, PM_REJECT, r);
    }
}

static void refuse(boot_bus *b, uint8_t function, uint8_t seq, fw_reason why, uint8_t field)
{
    const boot_verdict v = {why, field, 0, 0};
    answer(b, function, seq, &v);
}

static boot_image_status app_status(const boot_bus *b, boot_image_header *h)
{
    const boot_layout *l = b->up.layout;
    return boot_image_check((const uint8_t *)b->up.flash->mem + l->app_offset, l->app_bytes,
                            l->flash_base + l->app_offset, b->up.board, h);
}

static void query(boot_bus *b, uint8_t function, uint8_t seq)
{
    const boot_verdict ok = {FW_REASON_NONE, 0, 0, 0};
    answer(b, function, seq, &ok);
    const uint32_t board = b->up.board;
    const int32_t id[5] = {BOOT_VERSION_MAJOR, BOOT_VERSION_MINOR, (int32_t)(board & 0xFFFFu), (int32_t)(board >> 16),
                           BOOT_BLOCK_BYTES};
    send(b, PM_BOOT_ID, id);
    const boot_layout *l = b->up.layout;
    const int32_t layout[2] = {(int32_t)(l->flash_base + l->app_offset), (int32_t)l->app_bytes};
    send(b, PM_BOOT_LAYOUT, layout);
    boot_image_header h;
    const bool valid = app_status(b, &h) == BOOT_IMAGE_OK;
    const int32_t app[6] = {valid,
                            valid ? (int32_t)((h.version >> 16) & 0xFFu) : 0,
                            valid ? (int32_t)((h.version >> 8) & 0xFFu) : 0,
                            valid ? (int32_t)(h.version & 0xFFu) : 0,
                            valid ? (int32_t)(h.crc & 0xFFFFu) : 0,
                            valid ? (int32_t)(h.crc >> 16) : 0};
    send(b, PM_BOOT_APP, app);
}

static void data(boot_bus *b, const proto_message *m)
{
    uint8_t bytes[8];
    for (int k = 0; k < 4; ++k) {
        bytes[2 * k] = (uint8_t)m->v[k];
        bytes[2 * k + 1] = (uint8_t)(m->v[k] >> 8);
    }
    boot_verdict v;
    uint8_t seq;
    if (boot_update_data(&b->up, bytes, &v, &seq))
        answer(b, proto_wire[PM_BOOT_WRITE].function, seq, &v);
}

void boot_bus_frame(boot_bus *b, const hal_can_frame *f)
{
    if ((f->id & PROTO_NODE_MASK) != b->node)
        return; /* another's, or a broadcast: the bootloader honours none */
    const uint8_t function = (uint8_t)(f->id >> PROTO_NODE_BITS);
    proto_message m;
    const proto_error e = proto_decode(f, PROTO_TO_CONTROLLER, &m);
    if (e.reason != FW_REASON_NONE) {
        const proto_msg known = proto_find(function, PROTO_TO_CONTROLLER);
        const bool seq = e.reason == FW_REASON_RANGE && known != PM_COUNT && proto_wire[known].nfields &&
                         proto_wire[known].fields[0].seq;
        refuse(b, function, seq ? f->data[0] : 0, e.reason, e.field);
        return;
    }
    const uint8_t seq = proto_wire[m.msg].nfields && proto_wire[m.msg].fields[0].seq ? (uint8_t)m.v[0] : 0;
    boot_verdict v;
    switch (m.msg) {
    case PM_HOST_HEARTBEAT:
        return;
    case PM_BOOT_DATA:
        data(b, &m);
        return;
    case PM_BOOT_ENTER: /* already here: stays */
        v = (boot_verdict){FW_REASON_NONE, 0, 0, 0};
        break;
    case PM_BOOT_QUERY:
        query(b, function, seq);
        return;
    case PM_BOOT_ERASE:
        v = boot_update_erase(&b->up, (uint32_t)m.v[1]);
        break;
    case PM_BOOT_WRITE: {
        boot_verdict dropped;
        uint8_t dropped_seq;
        if (boot_update_write(&b->up, seq, (uint32_t)m.v[1], (uint32_t)m.v[2],
                              (uint32_t)m.v[3] | (uint32_t)m.v[4] << 16, &v, &dropped, &dropped_seq))
            answer(b, function, dropped_seq, &dropped);
        if (v.reason == FW_REASON_NONE)
            return; /* answered with its last frame */
        break;
    }
    case PM_BOOT_VERIFY:
        v = boot_update_verify(&b->up);
        break;
    case PM_BOOT_START: {
        boot_image_header h;
        const boot_image_status s = app_status(b, &h);
        v = s == BOOT_IMAGE_OK ? (boot_verdict){FW_REASON_NONE, 0, 0, 0}
                               : (boot_verdict){FW_REASON_NO_IMAGE, (uint8_t)s, 0, 0};
        b->start = s == BOOT_IMAGE_OK;
        break;
    }
    default: /* a controller's command: the application takes it, not the bootloader */
        v = (boot_verdict){FW_REASON_STATE, 0, 0, 0};
        break;
    }
    answer(b, function, seq, &v);
}
