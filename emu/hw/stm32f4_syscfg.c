/*
 * STM32F405/407 system configuration controller (SYSCFG, RM0090 section 9): the EXTI line
 * multiplexer, in place of QEMU's stm32f4xx_syscfg, which in 7.2 indexes its EXTICR registers
 * with the port as well as the pin and aborts on any pin change of port B or later.
 *
 * Modelled: EXTICR1..4 select which port's pin n drives EXTI line n (inputs "port*16 + pin"
 * for ports A..I); the selected pin's level goes to the EXTI line on every change, and at once
 * when the selection changes.  CMPCR's READY follows CMP_PD (the compensation cell is ready at
 * once).  Not modelled: MEMRMP's remapping (address 0 always shows the flash, as with BOOT0 low;
 * the register holds what is written), PMC.
 *
 * SPDX-License-Identifier: GPL-2.0-or-later
 */
#include "qemu/osdep.h"
#include "qemu/log.h"
#include "hw/sysbus.h"
#include "hw/irq.h"
#include "tse_f407.h"

OBJECT_DECLARE_SIMPLE_TYPE(Stm32f4SyscfgState, STM32F4_SYSCFG)

#define NUM_PORTS 9
#define R_MEMRMP 0x00
#define R_PMC 0x04
#define R_EXTICR1 0x08
#define R_CMPCR 0x20

struct Stm32f4SyscfgState {
    SysBusDevice parent_obj;
    MemoryRegion iomem;
    uint32_t memrmp, pmc, exticr[4], cmpcr;
    uint16_t level[NUM_PORTS];
    int sent[16];
    qemu_irq line[16];
};

static unsigned selected_port(Stm32f4SyscfgState *s, int pin)
{
    return (s->exticr[pin / 4] >> (4 * (pin % 4))) & 0xF;
}

static void send_line(Stm32f4SyscfgState *s, int pin)
{
    const unsigned port = selected_port(s, pin);
    const int l = port < NUM_PORTS ? (s->level[port] >> pin) & 1 : 0;
    if (l != s->sent[pin]) {
        s->sent[pin] = l;
        qemu_set_irq(s->line[pin], l);
    }
}

static void pin_in(void *opaque, int n, int level)
{
    Stm32f4SyscfgState *s = opaque;
    const int port = n / 16, pin = n % 16;
    s->level[port] = level ? s->level[port] | 1u << pin : s->level[port] & ~(1u << pin);
    send_line(s, pin);
}

static uint64_t syscfg_read(void *opaque, hwaddr addr, unsigned size)
{
    Stm32f4SyscfgState *s = opaque;
    switch (addr) {
    case R_MEMRMP:
        return s->memrmp;
    case R_PMC:
        return s->pmc;
    case R_EXTICR1 ... R_EXTICR1 + 12:
        return s->exticr[(addr - R_EXTICR1) / 4];
    case R_CMPCR:
        return s->cmpcr;
    }
    return 0;
}

static void syscfg_write(void *opaque, hwaddr addr, uint64_t val, unsigned size)
{
    Stm32f4SyscfgState *s = opaque;
    const uint32_t v = val;
    switch (addr) {
    case R_MEMRMP:
        s->memrmp = v & 3;
        if (v & 3) {
            qemu_log_mask(LOG_UNIMP, "stm32f4-syscfg: memory remap not modelled\n");
        }
        return;
    case R_PMC:
        s->pmc = v & (1u << 23);
        return;
    case R_EXTICR1 ... R_EXTICR1 + 12: {
        const int r = (addr - R_EXTICR1) / 4;
        s->exticr[r] = v & 0xFFFF;
        for (int pin = 4 * r; pin < 4 * r + 4; ++pin) {
            send_line(s, pin);
        }
        return;
    }
    case R_CMPCR:
        s->cmpcr = (v & 1) ? 0x101 : 0;
        return;
    }
    qemu_log_mask(LOG_GUEST_ERROR, "stm32f4-syscfg: write to 0x%" HWADDR_PRIx "\n", addr);
}

static const MemoryRegionOps syscfg_ops = {
    .read = syscfg_read,
    .write = syscfg_write,
    .endianness = DEVICE_LITTLE_ENDIAN,
    .valid = { .min_access_size = 4, .max_access_size = 4 },
};

static void syscfg_reset(DeviceState *dev)
{
    Stm32f4SyscfgState *s = STM32F4_SYSCFG(dev);
    s->memrmp = s->pmc = s->cmpcr = 0;
    memset(s->exticr, 0, sizeof s->exticr);
    for (int pin = 0; pin < 16; ++pin) {
        send_line(s, pin);
    }
}

static void syscfg_init(Object *obj)
{
    Stm32f4SyscfgState *s = STM32F4_SYSCFG(obj);
    memory_region_init_io(&s->iomem, obj, &syscfg_ops, s, "stm32f4-syscfg", 0x400);
    sysbus_init_mmio(SYS_BUS_DEVICE(obj), &s->iomem);
    qdev_init_gpio_in(DEVICE(obj), pin_in, 16 * NUM_PORTS);
    qdev_init_gpio_out(DEVICE(obj), s->line, 16);
    for (int pin = 0; pin < 16; ++pin) {
        s->sent[pin] = -1;
    }
}

static void syscfg_class_init(ObjectClass *klass, void *data)
{
    DEVICE_CLASS(klass)->reset = syscfg_reset;
}

static const TypeInfo syscfg_info = {
    .name = TYPE_STM32F4_SYSCFG,
    .parent = TYPE_SYS_BUS_DEVICE,
    .instance_size = sizeof(Stm32f4SyscfgState),
    .instance_init = syscfg_init,
    .class_init = syscfg_class_init,
};

static void syscfg_register_types(void)
{
    type_register_static(&syscfg_info);
}

type_init(syscfg_register_types)
