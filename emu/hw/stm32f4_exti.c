/*
 * STM32F405/407 external interrupt controller (EXTI, RM0090 section 12.3), in place of QEMU's
 * stm32f4xx_exti, which raises its interrupt on every change of an unmasked line whatever its
 * edge selection.
 *
 * Modelled: 23 lines (0..15 from SYSCFG's multiplexer, 16..22 inputs nothing drives here); a
 * line's rising (RTSR) or falling (FTSR) edge, or a 0-to-1 write of its SWIER bit, sets its PR
 * bit when IMR lets it through (RM0090 figure 41: the mask comes before the pending register);
 * PR is cleared by writing 1 (which also clears SWIER).  The interrupt lines to the NVIC are
 * levels, PR of the group's lines, in this order of sysbus IRQs: lines 0..4 (NVIC 6..10), 5..9
 * (23), 10..15 (40), 16 (1), 17 (41), 18 (42), 19 (62), 20 (76), 21 (2), 22 (3).
 * Not modelled: events (EMR holds what is written; nothing wakes from WFE through it).
 *
 * SPDX-License-Identifier: GPL-2.0-or-later
 */
#include "qemu/osdep.h"
#include "qemu/log.h"
#include "hw/sysbus.h"
#include "hw/irq.h"
#include "tse_f407.h"

OBJECT_DECLARE_SIMPLE_TYPE(Stm32f4ExtiState, STM32F4_EXTI)

#define R_IMR 0x00
#define R_EMR 0x04
#define R_RTSR 0x08
#define R_FTSR 0x0C
#define R_SWIER 0x10
#define R_PR 0x14
#define LINES_MASK ((1u << EXTI_NUM_LINES) - 1)

struct Stm32f4ExtiState {
    SysBusDevice parent_obj;
    MemoryRegion iomem;
    uint32_t imr, emr, rtsr, ftsr, swier, pr;
    uint32_t level; /* the inputs' levels */
    qemu_irq irq[EXTI_NUM_IRQS];
};

/* Which lines each interrupt output gathers. */
static const uint32_t irq_lines[EXTI_NUM_IRQS] = {
    1u << 0, 1u << 1, 1u << 2, 1u << 3, 1u << 4, 0x3E0u, 0xFC00u,
    1u << 16, 1u << 17, 1u << 18, 1u << 19, 1u << 20, 1u << 21, 1u << 22,
};

static void update(Stm32f4ExtiState *s)
{
    for (int i = 0; i < EXTI_NUM_IRQS; ++i) {
        qemu_set_irq(s->irq[i], (s->pr & irq_lines[i]) != 0);
    }
}

static void line_in(void *opaque, int line, int level)
{
    Stm32f4ExtiState *s = opaque;
    const uint32_t bit = 1u << line;
    const bool was = s->level & bit;
    level = level != 0;
    if (level == was) {
        return;
    }
    s->level = level ? s->level | bit : s->level & ~bit;
    if ((level ? s->rtsr : s->ftsr) & s->imr & bit) {
        s->pr |= bit;
        update(s);
    }
}

static uint64_t exti_read(void *opaque, hwaddr addr, unsigned size)
{
    Stm32f4ExtiState *s = opaque;
    switch (addr) {
    case R_IMR:
        return s->imr;
    case R_EMR:
        return s->emr;
    case R_RTSR:
        return s->rtsr;
    case R_FTSR:
        return s->ftsr;
    case R_SWIER:
        return s->swier;
    case R_PR:
        return s->pr;
    }
    return 0;
}

static void exti_write(void *opaque, hwaddr addr, uint64_t val, unsigned size)
{
    Stm32f4ExtiState *s = opaque;
    const uint32_t v = val & LINES_MASK;
    switch (addr) {
    case R_IMR:
        s->imr = v;
        break;
    case R_EMR:
        s->emr = v;
        break;
    case R_RTSR:
        s->rtsr = v;
        break;
    case R_FTSR:
        s->ftsr = v;
        break;
    case R_SWIER:
        s->pr |= v & ~s->swier & s->imr;
        s->swier |= v;
        break;
    case R_PR:
        s->pr &= ~v;
        s->swier &= ~v;
        break;
    default:
        qemu_log_mask(LOG_GUEST_ERROR, "stm32f4-exti: write to 0x%" HWADDR_PRIx "\n", addr);
        return;
    }
    update(s);
}

static const MemoryRegionOps exti_ops = {
    .read = exti_read,
    .write = exti_write,
    .endianness = DEVICE_LITTLE_ENDIAN,
    .valid = { .min_access_size = 4, .max_access_size = 4 },
};

static void exti_reset(DeviceState *dev)
{
    Stm32f4ExtiState *s = STM32F4_EXTI(dev);
    s->imr = s->emr = s->rtsr = s->ftsr = s->swier = s->pr = 0;
    update(s);
}

static void exti_init(Object *obj)
{
    Stm32f4ExtiState *s = STM32F4_EXTI(obj);
    memory_region_init_io(&s->iomem, obj, &exti_ops, s, "stm32f4-exti", 0x400);
    sysbus_init_mmio(SYS_BUS_DEVICE(obj), &s->iomem);
    for (int i = 0; i < EXTI_NUM_IRQS; ++i) {
        sysbus_init_irq(SYS_BUS_DEVICE(obj), &s->irq[i]);
    }
    qdev_init_gpio_in_named(DEVICE(obj), line_in, EXTI_IN_LINE, EXTI_NUM_LINES);
}

static void exti_class_init(ObjectClass *klass, void *data)
{
    DEVICE_CLASS(klass)->reset = exti_reset;
}

static const TypeInfo exti_info = {
    .name = TYPE_STM32F4_EXTI,
    .parent = TYPE_SYS_BUS_DEVICE,
    .instance_size = sizeof(Stm32f4ExtiState),
    .instance_init = exti_init,
    .class_init = exti_class_init,
};

static void exti_register_types(void)
{
    type_register_static(&exti_info);
}

type_init(exti_register_types)
