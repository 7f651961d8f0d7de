/*
 * STM32F405/407 general-purpose timer TIM2..TIM5 (RM0090 section 18), and TIM11 (section 19) as
 * far as its crystal measurement goes, in place of QEMU's stm32f2xx_timer, which counts at a
 * fixed 1 GHz, never wraps CNT at ARR, has no one-pulse mode and ignores URS and the prescaler's
 * preload.
 *
 * Modelled, up-counting: the counter runs at the "clk" input (the RCC's APB1 timer clock; the APB2
 * one for TIM11) divided by PSC+1 while CR1.CEN is set; on reaching ARR it wraps to 0 with an
 * update event (UEV) that loads PSC (always preloaded) and ARR (when ARPE) from their preload
 * registers and sets SR.UIF.  UDIS suppresses the UEV.  EGR.UG reinitialises the counter and the
 * prescaler, loads the preloads, and sets UIF unless URS (or UDIS).  One-pulse mode (OPM) clears
 * CEN at the UEV.  A write to CNT moves the counter.  ARR 0 blocks the counter.  A counter above
 * ARR counts on to its top (16 bits for TIM3/TIM4, 32 for TIM2/TIM5: property "width") and wraps
 * without an update.  The interrupt line is SR & DIER over UIF, CC1IF..CC4IF and TIF (a level).
 * A change of the input clock keeps the count reached and goes on at the new rate.
 * Input capture on channel 1 from an internal clock, TIM11's TI1 remapped to HSE_RTC (RM0090
 * section 19, TIM11_OR; the "ti1" clock input, selected where OR[1:0] is the "ti1-rmp"
 * property): with CCMR1's CC1S = 01 and CCER's CC1E, every IC1PSC-th rising edge of that clock
 * (1, 2, 4 or 8; counted afresh whenever the channel, OR or the clock changes) latches the
 * counter into CCR1, at the edge's time in virtual time, and sets CC1IF, or CC1OF as well when
 * CC1IF was still set; reading CCR1 clears CC1IF; CCR1 of a channel in input mode ignores
 * writes.  The edges are those of a clock started when the "ti1" clock last changed.  A capture
 * is computed when a register is read (a guest that polls costs nothing per edge), and timed by
 * a QEMU timer only while CC1IE is set.
 * Not modelled: down and centre-aligned counting, falling-edge capture (CC1P, CC1NP: logged),
 * the input filter and the synchroniser's delay, output compare, channels 2..4 (CCMRx, CCER,
 * CCRx hold what is written; no CCxIF, no output), capture from a pin, CC1G, slave modes and
 * triggers, DMA, CKD; TIM11's registers are TIM2..TIM5's (those it lacks are not refused).
 *
 * SPDX-License-Identifier: GPL-2.0-or-later
 */
#include "qemu/osdep.h"
#include "qemu/log.h"
#include "qemu/host-utils.h"
#include "qemu/timer.h"
#include "qapi/error.h"
#include "hw/sysbus.h"
#include "hw/irq.h"
#include "hw/qdev-clock.h"
#include "hw/qdev-properties.h"
#include "tse_f407.h"

OBJECT_DECLARE_SIMPLE_TYPE(Stm32f4TimState, STM32F4_TIM)

#define R_CR1 0x00
#define R_CR2 0x04
#define R_SMCR 0x08
#define R_DIER 0x0C
#define R_SR 0x10
#define R_EGR 0x14
#define R_CCMR1 0x18
#define R_CCMR2 0x1C
#define R_CCER 0x20
#define R_CNT 0x24
#define R_PSC 0x28
#define R_ARR 0x2C
#define R_CCR1 0x34
#define R_DCR 0x48
#define R_DMAR 0x4C
#define R_OR 0x50

#define CR1_CEN (1u << 0)
#define CR1_UDIS (1u << 1)
#define CR1_URS (1u << 2)
#define CR1_OPM (1u << 3)
#define CR1_DIR (1u << 4)
#define CR1_CMS (3u << 5)
#define CR1_ARPE (1u << 7)
#define SR_UIF (1u << 0)
#define SR_CC1IF (1u << 1)
#define SR_CC1OF (1u << 9)
#define DIER_CC1IE (1u << 1)
#define CCER_CC1E (1u << 0)
#define CCER_CC1P_NP ((1u << 1) | (1u << 3))
#define NO_RMP UINT32_MAX
#define SR_IRQ_BITS 0x5Fu /* UIF, CC1IF..CC4IF, TIF */
#define EGR_UG (1u << 0)

struct Stm32f4TimState {
    SysBusDevice parent_obj;
    MemoryRegion iomem;
    qemu_irq irq;
    Clock *clk;
    QEMUTimer *timer;
    uint32_t cr1, cr2, smcr, dier, sr, ccmr[2], ccer, psc, arr, ccr[4], dcr, or;
    uint32_t psc_active, arr_active; /* the shadow registers */
    /* The counter: cnt_base at t_base while running, cnt_base while stopped. */
    uint32_t cnt_base;
    int64_t t_base;
    int64_t next_uev; /* while running and scheduled */
    /* Channel 1's capture from the "ti1" clock: its edges are ti1_epoch + k periods, k >= 1;
     * the next capture is at edge ic_edge, time ic_next (INT64_MAX: none). */
    Clock *ti1;
    int64_t ti1_epoch;
    uint64_t ic_edge;
    int64_t ic_next;
    bool warned_polarity;
    uint32_t width;
    uint32_t ti1_rmp; /* OR[1:0] value connecting TI1 to the "ti1" clock; NO_RMP: none */
};

static uint32_t top(Stm32f4TimState *s)
{
    return s->width == 32 ? 0xFFFFFFFFu : 0xFFFFu;
}

static bool running(Stm32f4TimState *s)
{
    return (s->cr1 & CR1_CEN) && clock_get_hz(s->clk) != 0;
}

static void update_irq(Stm32f4TimState *s)
{
    qemu_set_irq(s->irq, (s->sr & s->dier & SR_IRQ_BITS) != 0);
}

/* The counter at `now` (no update event due before then: see catch_up). */
static uint32_t counter_at(Stm32f4TimState *s, int64_t now)
{
    if (!running(s) || s->arr_active == 0 || now <= s->t_base) {
        return s->cnt_base;
    }
    const uint64_t ticks = muldiv64(now - s->t_base, clock_get_hz(s->clk), NANOSECONDS_PER_SECOND);
    const uint64_t n = s->cnt_base + ticks / ((uint64_t)s->psc_active + 1);
    return n & top(s);
}

/* Counts from the counter at t_base to the next update event. */
static uint64_t counts_to_uev(Stm32f4TimState *s)
{
    const uint64_t arr = s->arr_active, cnt = s->cnt_base;
    return cnt <= arr ? arr + 1 - cnt : (uint64_t)top(s) - cnt + 1 + arr + 1;
}

/* The QEMU timer at the next event a guest can see without reading: an update event, or a
 * capture while its interrupt is enabled. */
static void arm_timer(Stm32f4TimState *s)
{
    if (!s->timer) {
        return; /* not realized yet */
    }
    int64_t t = s->next_uev;
    if ((s->dier & DIER_CC1IE) && s->ic_next < t) {
        t = s->ic_next;
    }
    if (t == INT64_MAX) {
        timer_del(s->timer);
    } else {
        timer_mod(s->timer, t);
    }
}

static void schedule(Stm32f4TimState *s)
{
    if (!running(s) || s->arr_active == 0) {
        s->next_uev = INT64_MAX;
        arm_timer(s);
        return;
    }
    const uint32_t hz = clock_get_hz(s->clk);
    const uint64_t ticks = counts_to_uev(s) * ((uint64_t)s->psc_active + 1);
    /* Rounded up: at next_uev the counter has reached its count (counter_at floors). */
    uint64_t ns = muldiv64(ticks, NANOSECONDS_PER_SECOND, hz);
    if (muldiv64(ns, hz, NANOSECONDS_PER_SECOND) < ticks) {
        ++ns;
    }
    s->next_uev = s->t_base + ns;
    arm_timer(s);
}

/* Freezes the count reached as the new base (before anything changes the rate or the count). */
static void rebase(Stm32f4TimState *s, int64_t now)
{
    s->cnt_base = counter_at(s, now);
    s->t_base = now;
}

static void load_shadows(Stm32f4TimState *s)
{
    s->psc_active = s->psc;
    if (s->cr1 & CR1_ARPE) {
        s->arr_active = s->arr;
    }
}

/* The update event at the counter's wrap, at time t. */
static void overflow(Stm32f4TimState *s, int64_t t)
{
    s->cnt_base = 0;
    s->t_base = t;
    if (!(s->cr1 & CR1_UDIS)) {
        load_shadows(s);
        s->sr |= SR_UIF;
    }
    if (s->cr1 & CR1_OPM) {
        s->cr1 &= ~CR1_CEN;
    }
    update_irq(s);
    schedule(s);
}

/* ---- channel 1's input capture ---- */

static bool capture_on(Stm32f4TimState *s)
{
    return (s->ccer & CCER_CC1E) && (s->ccmr[0] & 3) == 1 && s->ti1_rmp != NO_RMP &&
           (s->or & 3) == s->ti1_rmp && clock_get(s->ti1) != 0;
}

static unsigned ic1_prescaler(Stm32f4TimState *s)
{
    return 1u << ((s->ccmr[0] >> 2) & 3);
}

static int64_t edge_time(Stm32f4TimState *s, uint64_t k)
{
    const uint64_t ns = clock_ticks_to_ns(s->ti1, k);
    return ns > (uint64_t)(INT64_MAX - s->ti1_epoch) ? INT64_MAX : s->ti1_epoch + (int64_t)ns;
}

/* The prescaler counts edges afresh from now (RM0090: it is reset while CC1E is 0; here on any
 * change of what feeds the capture). */
static void capture_restart(Stm32f4TimState *s, int64_t now)
{
    if (!capture_on(s)) {
        s->ic_next = INT64_MAX;
        arm_timer(s);
        return;
    }
    if ((s->ccer & CCER_CC1P_NP) && !s->warned_polarity) {
        qemu_log_mask(LOG_UNIMP, "stm32f4-tim: capture on falling edges not modelled: rising\n");
        s->warned_polarity = true;
    }
    /* The first edge after now, then the prescaler's count of them. */
    const uint64_t first = (now > s->ti1_epoch ? clock_ns_to_ticks(s->ti1, now - s->ti1_epoch) : 0) + 1;
    s->ic_edge = first + ic1_prescaler(s) - 1;
    s->ic_next = edge_time(s, s->ic_edge);
    arm_timer(s);
}

/* The capture at time t: the counter then into CCR1 (every event before t has been taken). */
static void capture(Stm32f4TimState *s, int64_t t)
{
    if (s->sr & SR_CC1IF) {
        s->sr |= SR_CC1OF;
    }
    s->sr |= SR_CC1IF;
    s->ccr[0] = counter_at(s, t);
    s->ic_edge += ic1_prescaler(s);
    s->ic_next = edge_time(s, s->ic_edge);
    update_irq(s);
    arm_timer(s);
}

/* Takes the update events and captures due by now, in their order (the QEMU timer may not have
 * run yet): a capture reads the counter as of its own time. */
static void catch_up(Stm32f4TimState *s, int64_t now)
{
    for (;;) {
        const int64_t uev = running(s) ? s->next_uev : INT64_MAX;
        if (uev <= now && uev <= s->ic_next) {
            overflow(s, uev);
        } else if (s->ic_next <= now) {
            capture(s, s->ic_next);
        } else {
            return;
        }
    }
}

static void timer_cb(void *opaque)
{
    Stm32f4TimState *s = opaque;
    catch_up(s, qemu_clock_get_ns(QEMU_CLOCK_VIRTUAL));
}

static void ti1_changed(void *opaque, ClockEvent event)
{
    Stm32f4TimState *s = opaque;
    const int64_t now = qemu_clock_get_ns(QEMU_CLOCK_VIRTUAL);
    if (event == ClockPreUpdate) {
        catch_up(s, now);
    } else {
        s->ti1_epoch = now;
        capture_restart(s, now);
    }
}

static void clk_changed(void *opaque, ClockEvent event)
{
    Stm32f4TimState *s = opaque;
    const int64_t now = qemu_clock_get_ns(QEMU_CLOCK_VIRTUAL);
    if (event == ClockPreUpdate) {
        catch_up(s, now);
        rebase(s, now);
    } else {
        s->t_base = now;
        schedule(s);
    }
}

static uint64_t tim_read(void *opaque, hwaddr addr, unsigned size)
{
    Stm32f4TimState *s = opaque;
    const int64_t now = qemu_clock_get_ns(QEMU_CLOCK_VIRTUAL);
    catch_up(s, now);
    switch (addr) {
    case R_CR1:
        return s->cr1;
    case R_CR2:
        return s->cr2;
    case R_SMCR:
        return s->smcr;
    case R_DIER:
        return s->dier;
    case R_SR:
        return s->sr;
    case R_CCMR1:
    case R_CCMR2:
        return s->ccmr[(addr - R_CCMR1) / 4];
    case R_CCER:
        return s->ccer;
    case R_CNT:
        return counter_at(s, now);
    case R_PSC:
        return s->psc;
    case R_ARR:
        return s->arr;
    case R_CCR1 ... R_CCR1 + 12: {
        const unsigned ch = (addr - R_CCR1) / 4;
        /* A channel in input mode: the read clears its CCxIF (RM0090, TIMx_SR). */
        if ((s->ccmr[ch / 2] >> (8 * (ch % 2))) & 3) {
            s->sr &= ~(SR_CC1IF << ch);
            update_irq(s);
        }
        return s->ccr[ch];
    }
    case R_DCR:
        return s->dcr;
    case R_OR:
        return s->or;
    }
    return 0;
}

static void tim_write(void *opaque, hwaddr addr, uint64_t val, unsigned size)
{
    Stm32f4TimState *s = opaque;
    const uint32_t v = val;
    const int64_t now = qemu_clock_get_ns(QEMU_CLOCK_VIRTUAL);

    catch_up(s, now);
    switch (addr) {
    case R_CR1:
        if (v & (CR1_DIR | CR1_CMS)) {
            qemu_log_mask(LOG_UNIMP, "stm32f4-tim: only up-counting is modelled\n");
        }
        rebase(s, now);
        s->cr1 = v & 0x3FF;
        schedule(s);
        return;
    case R_CR2:
        s->cr2 = v & 0xF8;
        return;
    case R_SMCR:
        s->smcr = v & 0xFFF7;
        if (v & 7) {
            qemu_log_mask(LOG_UNIMP, "stm32f4-tim: slave modes not modelled\n");
        }
        return;
    case R_DIER:
        s->dier = v & 0x5F5F;
        update_irq(s);
        arm_timer(s);
        return;
    case R_SR:
        s->sr &= v | ~0x1E5Fu; /* rc_w0: writing 0 clears, writing 1 keeps */
        update_irq(s);
        return;
    case R_EGR:
        if (v & EGR_UG) {
            s->cnt_base = 0;
            s->t_base = now;
            if (!(s->cr1 & CR1_UDIS)) {
                s->psc_active = s->psc;
                s->arr_active = s->arr;
                if (!(s->cr1 & CR1_URS)) {
                    s->sr |= SR_UIF;
                }
            }
            update_irq(s);
            schedule(s);
        }
        if (v & ~EGR_UG) {
            qemu_log_mask(LOG_UNIMP, "stm32f4-tim: EGR 0x%x: only UG is modelled\n", v);
        }
        return;
    case R_CCMR1:
    case R_CCMR2:
        s->ccmr[(addr - R_CCMR1) / 4] = v;
        capture_restart(s, now);
        return;
    case R_CCER:
        s->ccer = v;
        capture_restart(s, now);
        return;
    case R_CNT:
        s->cnt_base = v & top(s);
        s->t_base = now;
        schedule(s);
        return;
    case R_PSC:
        s->psc = v & 0xFFFF; /* takes effect at the next update event */
        return;
    case R_ARR:
        s->arr = v & top(s);
        if (!(s->cr1 & CR1_ARPE)) {
            rebase(s, now);
            s->arr_active = s->arr;
            schedule(s);
        }
        return;
    case R_CCR1 ... R_CCR1 + 12: {
        const unsigned ch = (addr - R_CCR1) / 4;
        if (!((s->ccmr[ch / 2] >> (8 * (ch % 2))) & 3)) { /* read-only in input mode */
            s->ccr[ch] = v & top(s);
        }
        return;
    }
    case R_DCR:
        s->dcr = v & 0x1F1F;
        return;
    case R_DMAR:
        return;
    case R_OR:
        s->or = v;
        capture_restart(s, now);
        return;
    }
    qemu_log_mask(LOG_GUEST_ERROR, "stm32f4-tim: write to 0x%" HWADDR_PRIx "\n", addr);
}

static const MemoryRegionOps tim_ops = {
    .read = tim_read,
    .write = tim_write,
    .endianness = DEVICE_LITTLE_ENDIAN,
    .valid = { .min_access_size = 2, .max_access_size = 4 },
    .impl = { .min_access_size = 4, .max_access_size = 4 },
};

static void tim_reset(DeviceState *dev)
{
    Stm32f4TimState *s = STM32F4_TIM(dev);
    s->cr1 = s->cr2 = s->smcr = s->dier = s->sr = s->ccer = s->psc = s->dcr = s->or = 0;
    s->ccmr[0] = s->ccmr[1] = 0;
    memset(s->ccr, 0, sizeof s->ccr);
    s->arr = top(s);
    s->psc_active = 0;
    s->arr_active = s->arr;
    s->cnt_base = 0;
    s->t_base = qemu_clock_get_ns(QEMU_CLOCK_VIRTUAL);
    s->ic_next = INT64_MAX;
    s->warned_polarity = false;
    schedule(s);
    update_irq(s);
}

static void tim_init(Object *obj)
{
    Stm32f4TimState *s = STM32F4_TIM(obj);
    memory_region_init_io(&s->iomem, obj, &tim_ops, s, "stm32f4-tim", 0x400);
    sysbus_init_mmio(SYS_BUS_DEVICE(obj), &s->iomem);
    sysbus_init_irq(SYS_BUS_DEVICE(obj), &s->irq);
    s->clk = qdev_init_clock_in(DEVICE(obj), "clk", clk_changed, s, ClockPreUpdate | ClockUpdate);
    s->ti1 = qdev_init_clock_in(DEVICE(obj), "ti1", ti1_changed, s, ClockPreUpdate | ClockUpdate);
    s->next_uev = s->ic_next = INT64_MAX;
}

static void tim_realize(DeviceState *dev, Error **errp)
{
    Stm32f4TimState *s = STM32F4_TIM(dev);
    if (s->width != 16 && s->width != 32) {
        error_setg(errp, "stm32f4-tim: width must be 16 or 32");
        return;
    }
    s->timer = timer_new_ns(QEMU_CLOCK_VIRTUAL, timer_cb, s);
}

static Property tim_properties[] = {
    DEFINE_PROP_UINT32("width", Stm32f4TimState, width, 16),
    DEFINE_PROP_UINT32("ti1-rmp", Stm32f4TimState, ti1_rmp, NO_RMP),
    DEFINE_PROP_END_OF_LIST(),
};

static void tim_class_init(ObjectClass *klass, void *data)
{
    DeviceClass *dc = DEVICE_CLASS(klass);
    dc->realize = tim_realize;
    dc->reset = tim_reset;
    device_class_set_props(dc, tim_properties);
}

static const TypeInfo tim_info = {
    .name = TYPE_STM32F4_TIM,
    .parent = TYPE_SYS_BUS_DEVICE,
    .instance_size = sizeof(Stm32f4TimState),
    .instance_init = tim_init,
    .class_init = tim_class_init,
};

static void tim_register_types(void)
{
    type_register_static(&tim_info);
}

type_init(tim_register_types)
