/*
 * STM32F405/407 independent watchdog (IWDG, RM0090 section 19).
 *
 * Modelled: KR's keys (0xCCCC starts it, and nothing but a reset stops it; 0xAAAA reloads the
 * counter from RLR; 0x5555 opens PR and RLR to writes, any other key closes them again); PR and
 * RLR written while open reach the counter after 5 periods of the LSI, PVU/RVU in SR set until
 * then; the 12-bit counter counts down at lsi-hz / (4 << PR) and, when it reaches 0, resets the
 * system as a watchdog reset (the "reset" line to the RCC, which sets IWDGRSTF).  lsi-hz defaults
 * to the 32 kHz the firmware assumes (the part's LSI is 17..47 kHz).
 * Not modelled: the hardware watchdog option (WDG_SW), the debug freeze (a debugger's halt
 * stops all of virtual time here anyway).
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
#include "hw/qdev-properties.h"
#include "tse_f407.h"

OBJECT_DECLARE_SIMPLE_TYPE(Stm32f4IwdgState, STM32F4_IWDG)

#define R_KR 0x00
#define R_PR 0x04
#define R_RLR 0x08
#define R_SR 0x0C
#define SR_PVU (1u << 0)
#define SR_RVU (1u << 1)
#define UPDATE_LSI_PERIODS 5

struct Stm32f4IwdgState {
    SysBusDevice parent_obj;
    MemoryRegion iomem;
    qemu_irq reset, reload_out;
    QEMUTimer *expiry, *update;
    bool started, open;
    uint32_t pr, rlr, sr;            /* as written */
    uint32_t pr_active, rlr_active;  /* as the counter uses them */
    int64_t t_expiry;
    uint32_t lsi_hz;
};

static int64_t counts_ns(Stm32f4IwdgState *s, uint64_t counts, uint32_t pr)
{
    return muldiv64(counts * (4u << pr), NANOSECONDS_PER_SECOND, s->lsi_hz);
}

static void reload(Stm32f4IwdgState *s)
{
    s->t_expiry = qemu_clock_get_ns(QEMU_CLOCK_VIRTUAL) + counts_ns(s, s->rlr_active, s->pr_active);
    timer_mod(s->expiry, s->t_expiry);
}

static void expired(void *opaque)
{
    Stm32f4IwdgState *s = opaque;
    qemu_log_mask(LOG_GUEST_ERROR, "stm32f4-iwdg: counter reached 0: watchdog reset\n");
    s->started = false;
    qemu_irq_pulse(s->reset);
}

/* PR/RLR have crossed into the watchdog's clock domain. */
static void updated(void *opaque)
{
    Stm32f4IwdgState *s = opaque;
    const int64_t now = qemu_clock_get_ns(QEMU_CLOCK_VIRTUAL);
    if (s->started && s->pr != s->pr_active) {
        /* The counts left go on at the new rate. */
        const uint64_t left = muldiv64(s->t_expiry > now ? s->t_expiry - now : 0, s->lsi_hz,
                                       NANOSECONDS_PER_SECOND) / (4u << s->pr_active);
        s->t_expiry = now + counts_ns(s, left, s->pr);
        timer_mod(s->expiry, s->t_expiry);
    }
    s->pr_active = s->pr;
    s->rlr_active = s->rlr;
    s->sr = 0;
}

static uint64_t iwdg_read(void *opaque, hwaddr addr, unsigned size)
{
    Stm32f4IwdgState *s = opaque;
    switch (addr) {
    case R_PR:
        return s->pr;
    case R_RLR:
        return s->rlr;
    case R_SR:
        return s->sr;
    }
    return 0;
}

static void iwdg_write(void *opaque, hwaddr addr, uint64_t val, unsigned size)
{
    Stm32f4IwdgState *s = opaque;
    const uint32_t v = val;
    switch (addr) {
    case R_KR:
        switch (v & 0xFFFF) {
        case 0xCCCC:
            if (!s->started) {
                /* RM0090 19.3.2: it starts counting down from 0xFFF, whatever RLR holds. */
                s->started = true;
                s->t_expiry = qemu_clock_get_ns(QEMU_CLOCK_VIRTUAL) + counts_ns(s, 0xFFF, s->pr_active);
                timer_mod(s->expiry, s->t_expiry);
            }
            s->open = false;
            break;
        case 0xAAAA:
            if (s->started) {
                reload(s);
                qemu_irq_pulse(s->reload_out);
            }
            s->open = false;
            break;
        case 0x5555:
            s->open = true;
            break;
        default:
            s->open = false;
        }
        return;
    case R_PR:
    case R_RLR:
        if (!s->open) {
            qemu_log_mask(LOG_GUEST_ERROR, "stm32f4-iwdg: %s written without the 0x5555 key: ignored\n",
                          addr == R_PR ? "PR" : "RLR");
            return;
        }
        if (addr == R_PR) {
            s->pr = v & 7;
            s->sr |= SR_PVU;
        } else {
            s->rlr = v & 0xFFF;
            s->sr |= SR_RVU;
        }
        timer_mod(s->update, qemu_clock_get_ns(QEMU_CLOCK_VIRTUAL) +
                  muldiv64(UPDATE_LSI_PERIODS, NANOSECONDS_PER_SECOND, s->lsi_hz));
        return;
    }
}

static const MemoryRegionOps iwdg_ops = {
    .read = iwdg_read,
    .write = iwdg_write,
    .endianness = DEVICE_LITTLE_ENDIAN,
    .valid = { .min_access_size = 2, .max_access_size = 4 },
    .impl = { .min_access_size = 4, .max_access_size = 4 },
};

static void iwdg_reset(DeviceState *dev)
{
    Stm32f4IwdgState *s = STM32F4_IWDG(dev);
    timer_del(s->expiry);
    timer_del(s->update);
    s->started = s->open = false;
    s->pr = s->pr_active = 0;
    s->rlr = s->rlr_active = 0xFFF;
    s->sr = 0;
}

static void iwdg_realize(DeviceState *dev, Error **errp)
{
    Stm32f4IwdgState *s = STM32F4_IWDG(dev);
    if (s->lsi_hz == 0) {
        error_setg(errp, "stm32f4-iwdg: lsi-hz must not be 0");
        return;
    }
    s->expiry = timer_new_ns(QEMU_CLOCK_VIRTUAL, expired, s);
    s->update = timer_new_ns(QEMU_CLOCK_VIRTUAL, updated, s);
}

static void iwdg_init(Object *obj)
{
    Stm32f4IwdgState *s = STM32F4_IWDG(obj);
    memory_region_init_io(&s->iomem, obj, &iwdg_ops, s, "stm32f4-iwdg", 0x400);
    sysbus_init_mmio(SYS_BUS_DEVICE(obj), &s->iomem);
    qdev_init_gpio_out_named(DEVICE(obj), &s->reset, IWDG_OUT_RESET, 1);
    qdev_init_gpio_out_named(DEVICE(obj), &s->reload_out, IWDG_OUT_RELOAD, 1);
}

static Property iwdg_properties[] = {
    DEFINE_PROP_UINT32("lsi-hz", Stm32f4IwdgState, lsi_hz, 32000),
    DEFINE_PROP_END_OF_LIST(),
};

static void iwdg_class_init(ObjectClass *klass, void *data)
{
    DeviceClass *dc = DEVICE_CLASS(klass);
    dc->realize = iwdg_realize;
    dc->reset = iwdg_reset;
    device_class_set_props(dc, iwdg_properties);
}

static const TypeInfo iwdg_info = {
    .name = TYPE_STM32F4_IWDG,
    .parent = TYPE_SYS_BUS_DEVICE,
    .instance_size = sizeof(Stm32f4IwdgState),
    .instance_init = iwdg_init,
    .class_init = iwdg_class_init,
};

static void iwdg_register_types(void)
{
    type_register_static(&iwdg_info);
}

type_init(iwdg_register_types)
