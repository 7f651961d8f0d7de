#include "fake_hal.h"

#include "fw/runtime.h"

#include <string.h>

static int can_send(void *ctx, const hal_can_frame *fr)
{
    fake_hal *f = ctx;
    if (f->tx_count >= FAKE_QUEUE)
        return -1;
    f->tx[f->tx_count++] = *fr;
    return 0;
}

static void hook(fake_hal *f, fake_hook_point at)
{
    if (f->hook)
        f->hook(f->hook_arg, at);
}

static int can_receive(void *ctx, hal_can_frame *fr)
{
    fake_hal *f = ctx;
    hook(f, FAKE_AT_RECEIVE);
    if (f->rx_count == 0)
        return 0;
    *fr = f->rx[f->rx_head];
    f->rx_head = (f->rx_head + 1u) % FAKE_QUEUE;
    --f->rx_count;
    return 1;
}

static void can_state(void *ctx, hal_can_state *st)
{
    hook(ctx, FAKE_AT_CAN_STATE);
    *st = ((fake_hal *)ctx)->can_state;
}

static void set_dir(void *ctx, uint8_t mask)
{
    ((fake_hal *)ctx)->forward_mask = mask;
}

static void pulse(void *ctx, uint8_t mask)
{
    fake_hal *f = ctx;
    for (int k = 0; k < 6; ++k) {
        if ((mask >> k) & 1u) {
            f->steps[k] += ((f->forward_mask >> k) & 1u) ? 1 : -1;
            ++f->pulses;
        }
    }
}

static void enable(void *ctx, bool on)
{
    if (on)
        hook(ctx, FAKE_AT_ENABLE);
    ((fake_hal *)ctx)->enabled = on;
}

static void timing(void *ctx, uint32_t pulse_ns, uint32_t dir_setup_ns)
{
    fake_hal *f = ctx;
    f->pulse_ns = pulse_ns;
    f->dir_setup_ns = dir_setup_ns;
    ++f->timing_calls;
}

static uint16_t limits(void *ctx)
{
    fake_hal *f = ctx;
    uint16_t m = f->forced_limits;
    for (int k = 0; k < 6; ++k)
        if (f->steps[k] <= f->switch_at[k])
            m |= (uint16_t)(1u << k);
    return m;
}

static bool estop(void *ctx)
{
    return ((fake_hal *)ctx)->estop_open;
}

static uint64_t now(void *ctx)
{
    hook(ctx, FAKE_AT_CLOCK);
    return ((fake_hal *)ctx)->now_us;
}

static int load(void *ctx, void *buf, size_t cap)
{
    fake_hal *f = ctx;
    if (f->storage_len <= 0 || (size_t)f->storage_len > cap)
        return 0;
    memcpy(buf, f->storage, (size_t)f->storage_len);
    return f->storage_len;
}

static int save(void *ctx, const void *buf, size_t len)
{
    fake_hal *f = ctx;
    if (f->storage_fails || len > sizeof f->storage)
        return -1;
    memcpy(f->storage, buf, len);
    f->storage_len = (int)len;
    return 0;
}

void fake_hal_init(fake_hal *f, fw_hal *hal)
{
    memset(f, 0, sizeof *f);
    for (int k = 0; k < 6; ++k) {
        f->switch_at[k] = FAKE_SWITCH_AT;
        f->steps[k] = 384000 + 1000 * k; /* somewhere above the switches at power-up */
    }
    hal->can = (hal_can){f, can_send, can_receive, can_state};
    hal->stepper = (hal_stepper){f, set_dir, pulse, enable, timing};
    hal->inputs = (hal_inputs){f, limits, estop};
    hal->clock = (hal_clock){f, now};
    hal->storage = (hal_storage){f, load, save};
}

void fake_send(fake_hal *f, uint16_t id, uint8_t len, const uint8_t *data)
{
    hal_can_frame fr;
    memset(&fr, 0, sizeof fr);
    fr.id = id;
    fr.len = len;
    if (len)
        memcpy(fr.data, data, len > 8 ? 8 : len);
    f->rx[(f->rx_head + f->rx_count) % FAKE_QUEUE] = fr;
    ++f->rx_count;
}

int fake_encode(uint8_t node, proto_msg m, const int32_t *values, hal_can_frame *fr)
{
    return proto_encode_values(m, node, values, fr);
}

void fake_send_msg(fake_hal *f, uint8_t node, proto_msg m, const int32_t *values)
{
    hal_can_frame fr;
    if (fake_encode(node, m, values, &fr) == 0)
        fake_send(f, fr.id, fr.len, fr.data);
}

void fake_run(fake_hal *f, fw_controller *c, uint32_t ms)
{
    const uint32_t hz = fw_config_of(c)->segment_hz;
    for (uint32_t m = 0; m < ms * (hz / 1000u); ++m) {
        fw_run_period(c, NULL, NULL);
        f->now_us += 1000000u / hz;
    }
}

void fake_tick_alone(fake_hal *f, fw_controller *c)
{
    const fw_config *cfg = fw_config_of(c);
    f->now_us += 1000000u / cfg->segment_hz;
    fw_control_tick(c);
    for (uint32_t k = 0; k < cfg->step_hz / cfg->segment_hz; ++k)
        fw_step_tick(c);
}

const hal_can_frame *fake_last(const fake_hal *f, uint8_t function, unsigned from)
{
    for (unsigned i = f->tx_count; i > from; --i)
        if ((f->tx[i - 1].id >> 4) == function)
            return &f->tx[i - 1];
    return NULL;
}
