/*
 * STM32F405/407 general-purpose I/O port (GPIOx, RM0090 section 8), one instance a port.
 *
 * Modelled:
 * - MODER, OTYPER, OSPEEDR, PUPDR, AFRL/AFRH with the ports' reset values (port A and B differ:
 *   the debug pins), ODR, BSRR (set and reset in one write; set wins when both bits of a pin
 *   are written, RM0090 8.4.7), IDR, and the LCKR lock sequence (the pins locked keep their
 *   configuration until reset; a wrong sequence locks nothing).
 * - Each pin's level from its mode: a push-pull output drives ODR; an open-drain output drives
 *   0 or lets go; an input (or a released open-drain output, or an alternate-function pin) takes
 *   what drives it from outside ("ext" lines: 0, 1, or -1 for nothing), else its pull-up (1) or
 *   pull-down (0), else reads 0 (a floating input is undefined on the part); an analog pin reads
 *   0 in IDR.  Every change of a level goes out on the "pin" lines (to the board: the rig) and
 *   the "exti" lines (to SYSCFG's EXTI multiplexer).
 * - The alternate function of each pin in AF mode on the "af" lines (-1 otherwise), so a
 *   peripheral can tell whether it is connected to its pins (bxCAN checks PB8/PB9 on AF9).
 * Not modelled: output speed (stored only), electrical contention (an output wins over what
 *   drives the pin from outside), the signals of alternate functions on the pins.
 *
 * SPDX-License-Identifier: GPL-2.0-or-later
 */
#include "qemu/osdep.h"
#include "qemu/log.h"
#include "hw/sysbus.h"
#include "hw/irq.h"
#include "hw/qdev-properties.h"
#include "tse_f407.h"

OBJECT_DECLARE_SIMPLE_TYPE(Stm32f4GpioState, STM32F4_GPIO)

#define R_MODER 0x00
#define R_OTYPER 0x04
#define R_OSPEEDR 0x08
#define R_PUPDR 0x0C
#define R_IDR 0x10
#define R_ODR 0x14
#define R_BSRR 0x18
#define R_LCKR 0x1C
#define R_AFRL 0x20
#define R_AFRH 0x24
#define LCKK (1u << 16)

enum { MODE_INPUT, MODE_OUTPUT, MODE_AF, MODE_ANALOG };

struct Stm32f4GpioState {
    SysBusDevice parent_obj;
    MemoryRegion iomem;
    uint32_t moder, otyper, ospeedr, pupdr, odr, afr[2];
    uint32_t lckr;      /* LCK bits; LCKK once locked */
    int lock_step;      /* the LCKR sequence: 0 (none), 1, 2 writes done, 3 read pending */
    uint16_t idr;
    uint16_t level;     /* the pins' levels as last sent on the "pin" lines */
    int af_sent[16];
    int ext[16];        /* -1: nothing drives the pin from outside */
    qemu_irq pin_out[16];
    qemu_irq exti_out[16];
    qemu_irq af_out[16];
    uint8_t port;       /* 0 = A */
};

static unsigned field2(uint32_t reg, int pin)
{
    return (reg >> (2 * pin)) & 3;
}

static int pin_level(Stm32f4GpioState *s, int pin)
{
    const unsigned mode = field2(s->moder, pin);
    const bool odr = (s->odr >> pin) & 1;
    if (mode == MODE_OUTPUT && (!((s->otyper >> pin) & 1) || !odr)) {
        return odr;
    }
    if (s->ext[pin] >= 0) {
        return s->ext[pin];
    }
    switch (field2(s->pupdr, pin)) {
    case 1:
        return 1;
    default:
        return 0;
    }
}

/* Recomputes every pin; sends the changes. */
static void update(Stm32f4GpioState *s)
{
    uint16_t level = 0, idr = 0;
    for (int pin = 0; pin < 16; ++pin) {
        const int l = pin_level(s, pin);
        level |= l << pin;
        if (field2(s->moder, pin) != MODE_ANALOG) {
            idr |= l << pin;
        }
        const int af = field2(s->moder, pin) == MODE_AF ? (int)((s->afr[pin / 8] >> (4 * (pin % 8))) & 0xF) : -1;
        if (af != s->af_sent[pin]) {
            s->af_sent[pin] = af;
            qemu_set_irq(s->af_out[pin], af);
        }
    }
    s->idr = idr;
    const uint16_t changed = level ^ s->level;
    s->level = level;
    for (int pin = 0; pin < 16; ++pin) {
        if ((changed >> pin) & 1) {
            qemu_set_irq(s->pin_out[pin], (level >> pin) & 1);
            qemu_set_irq(s->exti_out[pin], (level >> pin) & 1);
        }
    }
}

static void ext_in(void *opaque, int pin, int level)
{
    Stm32f4GpioState *s = opaque;
    s->ext[pin] = level < 0 ? -1 : level != 0;
    update(s);
}

/* The configuration bits of the locked pins keep their value. */
static uint32_t keep_locked(uint32_t old, uint32_t v, uint16_t locked, int bits)
{
    uint32_t mask = 0;
    for (int pin = 0; pin < 16; ++pin) {
        if ((locked >> pin) & 1) {
            mask |= ((1u << bits) - 1) << (bits * pin);
        }
    }
    return (old & mask) | (v & ~mask);
}

static uint64_t gpio_read(void *opaque, hwaddr addr, unsigned size)
{
    Stm32f4GpioState *s = opaque;
    switch (addr) {
    case R_MODER:
        return s->moder;
    case R_OTYPER:
        return s->otyper;
    case R_OSPEEDR:
        return s->ospeedr;
    case R_PUPDR:
        return s->pupdr;
    case R_IDR:
        return s->idr;
    case R_ODR:
        return s->odr;
    case R_LCKR:
        if (s->lock_step == 3) {
            s->lckr |= LCKK; /* the sequence's read: the lock is active from here on */
            s->lock_step = 0;
        }
        return s->lckr;
    case R_AFRL:
        return s->afr[0];
    case R_AFRH:
        return s->afr[1];
    }
    return 0; /* BSRR reads 0 */
}

static void write_lckr(Stm32f4GpioState *s, uint32_t v)
{
    /* RM0090 8.4.8: LCKK=1, LCKK=0, LCKK=1 with the same LCK bits, then a read. */
    static const uint32_t want[3] = {LCKK, 0, LCKK};
    if (s->lckr & LCKK) {
        return; /* locked until reset */
    }
    if (s->lock_step < 3 && (v & LCKK) == want[s->lock_step] &&
        (s->lock_step == 0 || (v & 0xFFFF) == (s->lckr & 0xFFFF))) {
        s->lckr = v & 0xFFFF;
        ++s->lock_step;
    } else {
        s->lock_step = 0;
        s->lckr = 0;
    }
}

static void gpio_write(void *opaque, hwaddr addr, uint64_t val, unsigned size)
{
    Stm32f4GpioState *s = opaque;
    const uint32_t v = val;
    const uint16_t locked = (s->lckr & LCKK) ? s->lckr & 0xFFFF : 0;

    if (addr != R_LCKR && addr != R_IDR && s->lock_step != 0 && s->lock_step != 3) {
        s->lock_step = 0;
    }
    switch (addr) {
    case R_MODER:
        s->moder = keep_locked(s->moder, v, locked, 2);
        break;
    case R_OTYPER:
        s->otyper = keep_locked(s->otyper, v & 0xFFFF, locked, 1);
        break;
    case R_OSPEEDR:
        s->ospeedr = keep_locked(s->ospeedr, v, locked, 2);
        break;
    case R_PUPDR:
        s->pupdr = keep_locked(s->pupdr, v, locked, 2);
        break;
    case R_IDR:
        return;
    case R_ODR:
        s->odr = v & 0xFFFF;
        break;
    case R_BSRR:
        /* Both bits of a pin written: set wins (RM0090 8.4.7). */
        s->odr = (s->odr & ~(v >> 16)) | (v & 0xFFFF);
        break;
    case R_LCKR:
        write_lckr(s, v);
        return;
    case R_AFRL:
    case R_AFRH: {
        uint16_t half = 0;
        for (int pin = 0; pin < 8; ++pin) {
            half |= ((locked >> (pin + 8 * (addr == R_AFRH))) & 1) << pin;
        }
        s->afr[addr == R_AFRH] = keep_locked(s->afr[addr == R_AFRH], v, half, 4);
        break;
    }
    default:
        qemu_log_mask(LOG_GUEST_ERROR, "stm32f4-gpio: write to 0x%" HWADDR_PRIx "\n", addr);
        return;
    }
    update(s);
}

static const MemoryRegionOps gpio_ops = {
    .read = gpio_read,
    .write = gpio_write,
    .endianness = DEVICE_LITTLE_ENDIAN,
    .valid = { .min_access_size = 1, .max_access_size = 4 },
    .impl = { .min_access_size = 4, .max_access_size = 4 },
};

static void gpio_reset(DeviceState *dev)
{
    Stm32f4GpioState *s = STM32F4_GPIO(dev);
    s->moder = s->port == 0 ? 0xA8000000 : s->port == 1 ? 0x00000280 : 0;
    s->ospeedr = s->port == 0 ? 0x0C000000 : s->port == 1 ? 0x000000C0 : 0;
    s->pupdr = s->port == 0 ? 0x64000000 : s->port == 1 ? 0x00000100 : 0;
    s->otyper = 0;
    s->odr = 0;
    s->afr[0] = s->afr[1] = 0;
    s->lckr = 0;
    s->lock_step = 0;
    update(s);
}

static void gpio_init(Object *obj)
{
    Stm32f4GpioState *s = STM32F4_GPIO(obj);
    DeviceState *dev = DEVICE(obj);
    memory_region_init_io(&s->iomem, obj, &gpio_ops, s, "stm32f4-gpio", 0x400);
    sysbus_init_mmio(SYS_BUS_DEVICE(obj), &s->iomem);
    qdev_init_gpio_in_named(dev, ext_in, GPIO_IN_EXT, 16);
    qdev_init_gpio_out_named(dev, s->pin_out, GPIO_OUT_PIN, 16);
    qdev_init_gpio_out_named(dev, s->exti_out, GPIO_OUT_EXTI, 16);
    qdev_init_gpio_out_named(dev, s->af_out, GPIO_OUT_AF, 16);
    for (int pin = 0; pin < 16; ++pin) {
        s->ext[pin] = -1;
        s->af_sent[pin] = -2; /* sent at the first update */
    }
    s->level = 0;
}

static Property gpio_properties[] = {
    DEFINE_PROP_UINT8("port", Stm32f4GpioState, port, 0),
    DEFINE_PROP_END_OF_LIST(),
};

static void gpio_class_init(ObjectClass *klass, void *data)
{
    DeviceClass *dc = DEVICE_CLASS(klass);
    dc->reset = gpio_reset;
    device_class_set_props(dc, gpio_properties);
}

static const TypeInfo gpio_info = {
    .name = TYPE_STM32F4_GPIO,
    .parent = TYPE_SYS_BUS_DEVICE,
    .instance_size = sizeof(Stm32f4GpioState),
    .instance_init = gpio_init,
    .class_init = gpio_class_init,
};

static void gpio_register_types(void)
{
    type_register_static(&gpio_info);
}

type_init(gpio_register_types)
