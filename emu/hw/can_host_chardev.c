/*
 * can-host-chardev: a QEMU CAN bus bridged to a character device, in the place can-host-socketcan
 * takes where the host kernel has SocketCAN.  QEMU 7.2 accepts only the object types of its QAPI
 * schema on -object, so the machine creates it (tse_f407.c: -M tse-f407,can-chardev=ID,bitrate=B
 * with -chardev socket,id=ID,...).
 *
 * The byte stream carries one 16-byte record a frame, both ways, little-endian:
 *   u32 can_id   SocketCAN's layout: bit 31 extended, bit 30 RTR, bit 29 error frame; the
 *                identifier in bits 0..10 (standard) or 0..28 (extended)
 *   u8  len      0..8
 *   u8  flags    0
 *   u16 reserved 0
 *   u8  data[8]  the first len bytes count; the rest are sent as 0
 * A record with len above 8, non-zero flags or reserved bytes, an error frame, or an identifier
 * with bits beyond its format's is refused (a warning names the field) and nothing of it reaches
 * the bus.
 *
 * Towards the bus the bridge is a node like any other: the frames written to the chardev go on
 * the bus one after the other, each taking its nominal time at `bitrate` (44 + 8 len + 3 bits,
 * 64 + ... extended), so no node sees frames faster than a real bus carries them; up to 64 wait
 * (then the bridge stops reading the chardev: flow control).  It acknowledges the frames of the
 * other nodes while something is connected to the chardev (a node with nobody behind it is
 * like a bus with no other node: the controller's frames get no acknowledgement), and writes
 * them out; what the reader does not take is buffered (64 KiB), then dropped whole records at a
 * time, counted in a warning.
 *
 * SPDX-License-Identifier: GPL-2.0-or-later
 */
#include "qemu/osdep.h"
#include "qemu/error-report.h"
#include "qemu/host-utils.h"
#include "qemu/timer.h"
#include "qapi/error.h"
#include "qom/object_interfaces.h"
#include "chardev/char-fe.h"
#include "qapi/visitor.h"
#include "net/can_emu.h"
#include "net/can_host.h"
#include "tse_f407.h"

OBJECT_DECLARE_SIMPLE_TYPE(CanHostChardev, CAN_HOST_CHARDEV)

#define RECORD 16
#define QUEUE 64
#define OUT_BYTES 65536

struct CanHostChardev {
    CanHostState parent;
    char *chardev_id;
    uint32_t bitrate;
    CharBackend chr;
    bool connected;

    uint8_t partial[RECORD];
    unsigned partial_len;
    qemu_can_frame queue[QUEUE];
    unsigned q_head, q_len;
    QEMUTimer *timer;
    int64_t bus_free; /* when the frame we put on the bus ends */

    uint8_t out[OUT_BYTES];
    unsigned out_len;
    guint watch;
    uint64_t dropped;
};

/* ---- chardev to bus ---- */

static uint32_t frame_bits(const qemu_can_frame *f)
{
    return tse_can_frame_bits(f->can_id & QEMU_CAN_EFF_FLAG, f->can_id & QEMU_CAN_RTR_FLAG, f->can_dlc);
}

static void deliver(void *opaque)
{
    CanHostChardev *c = opaque;
    const int64_t now = qemu_clock_get_ns(QEMU_CLOCK_VIRTUAL);
    if (c->q_len == 0) {
        return;
    }
    if (now < c->bus_free) {
        timer_mod(c->timer, c->bus_free);
        return;
    }
    /* The frame at the head has had its time on the bus: hand it to the other nodes. */
    can_bus_client_send(&c->parent.bus_client, &c->queue[c->q_head], 1);
    c->q_head = (c->q_head + 1) % QUEUE;
    --c->q_len;
    if (c->q_len) {
        c->bus_free = now + muldiv64(frame_bits(&c->queue[c->q_head]), NANOSECONDS_PER_SECOND, c->bitrate);
        timer_mod(c->timer, c->bus_free);
    }
    qemu_chr_fe_accept_input(&c->chr);
}

/* Checks a record; fills *f and returns NULL, or returns what is wrong. */
static const char *parse_record(const uint8_t *r, qemu_can_frame *f)
{
    const uint32_t id = ldl_le_p(r);
    const bool eff = id & QEMU_CAN_EFF_FLAG;
    if (id & QEMU_CAN_ERR_FLAG) {
        return "can_id has the error-frame bit (29) set";
    }
    if (eff ? (id & 0x1FFFFFFF) != (id & ~(QEMU_CAN_EFF_FLAG | QEMU_CAN_RTR_FLAG))
            : (id & ~(QEMU_CAN_RTR_FLAG)) > QEMU_CAN_SFF_MASK) {
        return "can_id has bits beyond its identifier format";
    }
    if (r[4] > 8) {
        return "len above 8";
    }
    if (r[5] != 0) {
        return "flags not 0";
    }
    if (r[6] != 0 || r[7] != 0) {
        return "reserved bytes not 0";
    }
    memset(f, 0, sizeof *f);
    f->can_id = id;
    f->can_dlc = r[4];
    memcpy(f->data, r + 8, r[4]);
    return NULL;
}

static void take_record(CanHostChardev *c, const uint8_t *r)
{
    qemu_can_frame f;
    const char *why = parse_record(r, &f);
    if (why) {
        warn_report("can-host-chardev: record refused: %s (can_id 0x%08x len %u)", why, ldl_le_p(r), r[4]);
        return;
    }
    const int64_t now = qemu_clock_get_ns(QEMU_CLOCK_VIRTUAL);
    c->queue[(c->q_head + c->q_len) % QUEUE] = f;
    if (c->q_len++ == 0) {
        const int64_t start = now > c->bus_free ? now : c->bus_free;
        c->bus_free = start + muldiv64(frame_bits(&f), NANOSECONDS_PER_SECOND, c->bitrate);
        timer_mod(c->timer, c->bus_free);
    }
}

static int chr_can_read(void *opaque)
{
    CanHostChardev *c = opaque;
    const unsigned room = QUEUE - c->q_len;
    return room ? room * RECORD - c->partial_len : 0;
}

static void chr_read(void *opaque, const uint8_t *buf, int size)
{
    CanHostChardev *c = opaque;
    for (int i = 0; i < size; ++i) {
        c->partial[c->partial_len++] = buf[i];
        if (c->partial_len == RECORD) {
            c->partial_len = 0;
            take_record(c, c->partial);
        }
    }
}

static void chr_event(void *opaque, QEMUChrEvent event)
{
    CanHostChardev *c = opaque;
    if (event == CHR_EVENT_OPENED) {
        c->connected = true;
    } else if (event == CHR_EVENT_CLOSED) {
        c->connected = false;
        c->partial_len = 0;
        c->out_len = 0;
    }
}

/* ---- bus to chardev ---- */

static gboolean flush_out(void *do_not_use, GIOCondition cond, void *opaque)
{
    CanHostChardev *c = opaque;
    c->watch = 0;
    if (!c->connected) {
        c->out_len = 0;
        return G_SOURCE_REMOVE;
    }
    const int n = qemu_chr_fe_write(&c->chr, c->out, c->out_len);
    if (n > 0) {
        memmove(c->out, c->out + n, c->out_len - n);
        c->out_len -= n;
    }
    if (c->out_len) {
        c->watch = qemu_chr_fe_add_watch(&c->chr, G_IO_OUT | G_IO_HUP, flush_out, c);
        if (!c->watch) {
            c->out_len = 0; /* the backend cannot say when it is writable: give up */
        }
    }
    return G_SOURCE_REMOVE;
}

static bool bus_can_receive(CanBusClientState *client)
{
    return true;
}

static ssize_t bus_receive(CanBusClientState *client, const qemu_can_frame *frames, size_t n)
{
    CanHostChardev *c = container_of(container_of(client, CanHostState, bus_client), CanHostChardev, parent);
    if (!c->connected) {
        return 0; /* nobody there to acknowledge */
    }
    for (size_t i = 0; i < n; ++i) {
        uint8_t r[RECORD] = { 0 };
        if (frames[i].flags & QEMU_CAN_FRMF_TYPE_FD) {
            continue;
        }
        stl_le_p(r, frames[i].can_id);
        r[4] = MIN(frames[i].can_dlc, 8);
        memcpy(r + 8, frames[i].data, r[4]);
        if (c->out_len + RECORD > OUT_BYTES) {
            if (c->dropped++ % 1000 == 0) {
                warn_report("can-host-chardev: the reader is not keeping up: %" PRIu64
                            " frames dropped", c->dropped);
            }
            continue;
        }
        memcpy(c->out + c->out_len, r, RECORD);
        c->out_len += RECORD;
    }
    if (!c->watch && c->out_len) {
        flush_out(NULL, G_IO_OUT, c);
    }
    return 1;
}

static CanBusClientInfo bus_client_info = {
    .can_receive = bus_can_receive,
    .receive = bus_receive,
};

/* ---- object ---- */

static void chardev_connect(CanHostState *ch, Error **errp)
{
    CanHostChardev *c = CAN_HOST_CHARDEV(ch);
    Chardev *chr = c->chardev_id ? qemu_chr_find(c->chardev_id) : NULL;
    if (!chr) {
        error_setg(errp, "can-host-chardev: no chardev '%s'", c->chardev_id ? c->chardev_id : "");
        return;
    }
    if (c->bitrate == 0) {
        error_setg(errp, "can-host-chardev: bitrate must not be 0");
        return;
    }
    if (!qemu_chr_fe_init(&c->chr, chr, errp)) {
        return;
    }
    ch->bus_client.info = &bus_client_info;
    c->timer = timer_new_ns(QEMU_CLOCK_VIRTUAL, deliver, c);
    qemu_chr_fe_set_handlers(&c->chr, chr_can_read, chr_read, chr_event, NULL, c, NULL, true);
}

static void chardev_disconnect(CanHostState *ch)
{
    CanHostChardev *c = CAN_HOST_CHARDEV(ch);
    qemu_chr_fe_deinit(&c->chr, false);
}

static char *get_chardev(Object *obj, Error **errp)
{
    return g_strdup(CAN_HOST_CHARDEV(obj)->chardev_id);
}

static void set_chardev(Object *obj, const char *value, Error **errp)
{
    CanHostChardev *c = CAN_HOST_CHARDEV(obj);
    g_free(c->chardev_id);
    c->chardev_id = g_strdup(value);
}

static void get_bitrate(Object *obj, Visitor *v, const char *name, void *opaque, Error **errp)
{
    visit_type_uint32(v, name, &CAN_HOST_CHARDEV(obj)->bitrate, errp);
}

static void set_bitrate(Object *obj, Visitor *v, const char *name, void *opaque, Error **errp)
{
    visit_type_uint32(v, name, &CAN_HOST_CHARDEV(obj)->bitrate, errp);
}

static void chardev_instance_init(Object *obj)
{
    CAN_HOST_CHARDEV(obj)->bitrate = 500000;
}

static void chardev_class_init(ObjectClass *klass, void *data)
{
    CanHostClass *chc = CAN_HOST_CLASS(klass);
    object_class_property_add_str(klass, "chardev", get_chardev, set_chardev);
    object_class_property_add(klass, "bitrate", "uint32", get_bitrate, set_bitrate, NULL, NULL);
    chc->connect = chardev_connect;
    chc->disconnect = chardev_disconnect;
}

static const TypeInfo chardev_info = {
    .parent = TYPE_CAN_HOST,
    .name = TYPE_CAN_HOST_CHARDEV,
    .instance_size = sizeof(CanHostChardev),
    .instance_init = chardev_instance_init,
    .class_init = chardev_class_init,
};

static void chardev_register_types(void)
{
    type_register_static(&chardev_info);
}

type_init(chardev_register_types)
