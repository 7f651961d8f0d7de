#include "hal_fault/fault_can.h"

#include <string.h>

void fault_can_init(fault_can *fc, const fault_can_config *cfg, hal_can inner, hal_clock clock)
{
    memset(fc, 0, sizeof *fc);
    fc->cfg = *cfg;
    fc->inner = inner;
    fault_clock_init(&fc->clock, clock);
    fault_rng_seed(&fc->rng, cfg->seed);
}

static void tap(const fault_can *fc, fault_can_tap what, const hal_can_frame *f)
{
    if (fc->cfg.tap)
        fc->cfg.tap(fc->cfg.tap_arg, what, f);
}

static bool hold(fault_can *fc, const hal_can_frame *f, uint64_t release_us, bool reorder)
{
    if (fc->nheld == FAULT_CAN_HOLD)
        return false; /* no room: the frame goes through unharmed */
    fault_held *h = &fc->held[fc->nheld++];
    h->f = *f;
    h->release_us = release_us;
    h->after = fc->stats.delivered;
    h->reorder = reorder;
    return true;
}

/* The first held frame that is due, taken out of the queue. */
static bool take_due(fault_can *fc, uint64_t now, hal_can_frame *out)
{
    for (unsigned i = 0; i < fc->nheld; ++i) {
        const fault_held *h = &fc->held[i];
        if (now >= h->release_us || (h->reorder && fc->stats.delivered > h->after)) {
            *out = h->f;
            memmove(&fc->held[i], &fc->held[i + 1], (fc->nheld - i - 1) * sizeof fc->held[0]);
            --fc->nheld;
            return true;
        }
    }
    return false;
}

static fault_can_kind draw(fault_can *fc)
{
    const double u = fault_rng_unit(&fc->rng);
    double edge = 0.0;
    for (int k = 0; k < FAULT_CAN_KINDS; ++k) {
        edge += fc->cfg.p[k];
        if (u < edge)
            return (fault_can_kind)k;
    }
    return FAULT_CAN_KINDS; /* none */
}

/* Returns whether the frame was changed. */
static bool corrupt(fault_can *fc, hal_can_frame *f)
{
    fault_corrupt_how how = fc->cfg.corrupt_how;
    if (how == FAULT_CORRUPT_ANY) {
        const uint32_t r = fault_rng_below(&fc->rng, 4);
        how = r < 2 ? FAULT_CORRUPT_PAYLOAD : r == 2 ? FAULT_CORRUPT_LENGTH : FAULT_CORRUPT_ID;
    }
    if (how == FAULT_CORRUPT_PAYLOAD && f->len == 0)
        how = FAULT_CORRUPT_LENGTH; /* no payload to flip */
    hal_can_frame g = *f;
    if (how == FAULT_CORRUPT_PAYLOAD)
        g.data[fault_rng_below(&fc->rng, g.len)] ^= (uint8_t)(1u << fault_rng_below(&fc->rng, 8));
    else if (how == FAULT_CORRUPT_LENGTH)
        g.len = (uint8_t)((g.len + 1u + fault_rng_below(&fc->rng, 8)) % 9u); /* any other of 0..8 */
    else
        g.id = (uint16_t)(g.id ^ (1u << fault_rng_below(&fc->rng, 11)));
    if (fc->cfg.spare && fc->cfg.spare(fc->cfg.spare_arg, f, &g)) {
        ++fc->stats.spared;
        return false;
    }
    *f = g;
    if (how == FAULT_CORRUPT_PAYLOAD)
        ++fc->stats.corrupt_payload;
    else if (how == FAULT_CORRUPT_LENGTH)
        ++fc->stats.corrupt_length;
    else
        ++fc->stats.corrupt_id;
    return true;
}

static int hand_over(fault_can *fc, const hal_can_frame *f)
{
    ++fc->stats.delivered;
    tap(fc, FAULT_TAP_DELIVERED, f);
    return 1;
}

static int receive(void *ctx, hal_can_frame *out)
{
    fault_can *fc = ctx;
    const uint64_t now = fault_clock_us(&fc->clock);
    if (fault_window_holds(&fc->cfg.bus_off, now)) {
        /* A bus-off controller takes nothing off the bus; what was held stays held. */
        hal_can_frame lost;
        while (fc->inner.receive(fc->inner.ctx, &lost) == 1) {
            ++fc->stats.received;
            ++fc->stats.bus_off_lost;
        }
        return 0;
    }
    for (;;) {
        if (take_due(fc, now, out))
            return hand_over(fc, out);
        hal_can_frame f;
        if (fc->inner.receive(fc->inner.ctx, &f) != 1)
            return 0;
        ++fc->stats.received;
        if (fault_window_holds(&fc->cfg.silence, now)) {
            ++fc->stats.silenced;
            continue;
        }
        const fault_can_kind k = draw(fc);
        bool faulted = false;
        switch (k) {
        case FAULT_DROP:
            faulted = true;
            break;
        case FAULT_DUP:
            faulted = hold(fc, &f, 0, false); /* due at once: right after the original */
            break;
        case FAULT_REORDER:
            faulted = hold(fc, &f, now + fc->cfg.delay_us, true);
            break;
        case FAULT_DELAY:
            faulted = hold(fc, &f, now + fc->cfg.delay_us, false);
            break;
        case FAULT_CORRUPT:
            faulted = corrupt(fc, &f);
            break;
        case FAULT_CAN_KINDS:
            break;
        }
        if (faulted)
            ++fc->stats.faults[k];
        if (faulted && (k == FAULT_DROP || k == FAULT_REORDER || k == FAULT_DELAY))
            continue;
        *out = f;
        return hand_over(fc, out);
    }
}

static int send(void *ctx, const hal_can_frame *f)
{
    fault_can *fc = ctx;
    ++fc->stats.sent;
    tap(fc, FAULT_TAP_SENT, f);
    if (fault_window_holds(&fc->cfg.bus_off, fault_clock_us(&fc->clock))) {
        ++fc->stats.send_refused;
        return -1;
    }
    return fc->inner.send(fc->inner.ctx, f);
}

static void state(void *ctx, hal_can_state *st)
{
    fault_can *fc = ctx;
    fc->inner.state(fc->inner.ctx, st);
    const uint64_t now = fault_clock_us(&fc->clock);
    const fault_window *w = &fc->cfg.bus_off;
    /* A window begun counts once, whether or not a look fell inside it. */
    if (!fault_window_empty(w) && now >= w->from_us &&
        (w->from_us != fc->counted.from_us || w->until_us != fc->counted.until_us)) {
        fc->counted = *w;
        ++fc->stats.bus_off_events;
    }
    st->bus_off_events += fc->stats.bus_off_events;
    if (fault_window_holds(w, now)) {
        st->bus_off = true;
        st->error_passive = true;
        st->tx_errors = 255;
    }
}

hal_can fault_can_hal(fault_can *fc)
{
    return (hal_can){fc, send, receive, state};
}
