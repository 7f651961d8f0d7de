#include "inbox.h"

#include "fw/work.h"
#include "state.h"
#include "telemetry.h"

bool fw_inbox_next(fw_controller *c, hal_can_frame *f)
{
    fw_thread *th = &c->th;
    if (th->in_count > 0) {
        *f = th->inbox[th->in_head];
        th->in_head = (th->in_head + 1u) % FW_INBOX;
        --th->in_count;
        return true;
    }
    return fw_inbox_receive(c, f);
}

bool fw_inbox_receive(fw_controller *c, hal_can_frame *f)
{
    const uint32_t t = fw_now32(c); /* before the look: whatever came before it, the look finds */
    if (c->hal.can.receive(c->hal.can.ctx, f) == 1)
        return true;
    atomic_store(&c->sh.bus_read_us, t);
    return false;
}

/* The command message of a frame to this controller (or a broadcast), by its function code and
 * length alone (the full decode comes in its turn); PM_COUNT for anything else. */
static proto_msg command_of(const fw_controller *c, const hal_can_frame *f)
{
    const uint8_t node = (uint8_t)(f->id & PROTO_NODE_MASK);
    if (f->id > HAL_CAN_MAX_ID || (node != c->cfg.node && node != PROTO_BROADCAST))
        return PM_COUNT;
    const proto_msg m = proto_find((uint8_t)(f->id >> PROTO_NODE_BITS), PROTO_TO_CONTROLLER);
    if (m == PM_COUNT || f->len != proto_wire[m].dlc)
        return PM_COUNT;
    if (node == PROTO_BROADCAST && m != PM_STOP && m != PM_ESTOP)
        return PM_COUNT;
    return m;
}

static bool watch(void *ctx)
{
    fw_controller *c = ctx;
    fw_thread *th = &c->th;
    atomic_fetch_add_explicit(&c->sh.progress, 1u, memory_order_relaxed);
    hal_can_frame f;
    while (th->in_count < FW_INBOX && fw_inbox_receive(c, &f)) {
        const proto_msg m = command_of(c, &f);
        if (m == PM_HOST_HEARTBEAT) {
            atomic_store(&c->sh.heartbeat_us, fw_now32(c));
            continue;
        }
        th->inbox[(th->in_head + th->in_count) % FW_INBOX] = f;
        ++th->in_count;
        if (m == PM_ESTOP) {
            fw_estop_halt(c);
            th->abandon = true;
        } else if (m == PM_STOP && th->watch_moving) {
            th->abandon = true;
        }
    }
    fw_telemetry_look(c);
    return th->abandon;
}

void fw_inbox_look(fw_controller *c)
{
    const bool abandon = c->th.abandon;
    watch(c);
    c->th.abandon = abandon; /* a look ends no validation */
}

void fw_inbox_watch_begin(fw_controller *c, bool moving)
{
    c->th.watch_moving = moving;
    c->th.abandon = false;
    fw_work_begin(watch, c);
}

bool fw_inbox_watch_end(fw_controller *c)
{
    fw_work_end();
    /* The bus once more: a STOP that came after the last look still counts for this commit. */
    watch(c);
    const bool ended = c->th.abandon;
    c->th.abandon = false;
    return ended;
}

bool fw_inbox_take_stop(fw_controller *c, hal_can_frame *f)
{
    fw_thread *th = &c->th;
    for (unsigned i = 0; i < th->in_count; ++i) {
        const hal_can_frame *g = &th->inbox[(th->in_head + i) % FW_INBOX];
        const proto_msg m = command_of(c, g);
        if (m != PM_STOP && m != PM_ESTOP)
            continue;
        *f = *g;
        for (unsigned j = i; j + 1u < th->in_count; ++j)
            th->inbox[(th->in_head + j) % FW_INBOX] = th->inbox[(th->in_head + j + 1u) % FW_INBOX];
        --th->in_count;
        return true;
    }
    return false;
}
