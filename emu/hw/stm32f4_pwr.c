/*
 * STM32F405/407 power controller (PWR, RM0090 section 5.4): CR holds what is written (VOS,
 * reset value scale 1, DBP, ...), CSR reports the regulator ready in the scale selected
 * (VOSRDY) and nothing else.  Not modelled: the voltage detector, standby and stop modes, the
 * backup regulator, wake-up flags.
 *
 * SPDX-License-Identifier: GPL-2.0-or-later
 */
#include "qemu/osdep.h"
#include "qemu/log.h"
#include "hw/sysbus.h"
#include "tse_f407.h"

OBJECT_DECLARE_SIMPLE_TYPE(Stm32f4PwrState, STM32F4_PWR)

#define R_CR 0x00
#define R_CSR 0x04
#define CR_VOS (1u << 14)
#define CSR_VOSRDY (1u << 14)

struct Stm32f4PwrState {
    SysBusDevice parent_obj;
    MemoryRegion iomem;
    uint32_t cr;
};

static uint64_t pwr_read(void *opaque, hwaddr addr, unsigned size)
{
    Stm32f4PwrState *s = opaque;
    switch (addr) {
    case R_CR:
        return s->cr;
    case R_CSR:
        return CSR_VOSRDY;
    }
    return 0;
}

static void pwr_write(void *opaque, hwaddr addr, uint64_t val, unsigned size)
{
    Stm32f4PwrState *s = opaque;
    if (addr == R_CR) {
        s->cr = val & 0x0000C3FF;
    } else if (addr != R_CSR) {
        qemu_log_mask(LOG_GUEST_ERROR, "stm32f4-pwr: write to 0x%" HWADDR_PRIx "\n", addr);
    }
}

static const MemoryRegionOps pwr_ops = {
    .read = pwr_read,
    .write = pwr_write,
    .endianness = DEVICE_LITTLE_ENDIAN,
    .valid = { .min_access_size = 1, .max_access_size = 4 },
    .impl = { .min_access_size = 4, .max_access_size = 4 },
};

static void pwr_reset(DeviceState *dev)
{
    STM32F4_PWR(dev)->cr = CR_VOS;
}

static void pwr_init(Object *obj)
{
    Stm32f4PwrState *s = STM32F4_PWR(obj);
    memory_region_init_io(&s->iomem, obj, &pwr_ops, s, "stm32f4-pwr", 0x400);
    sysbus_init_mmio(SYS_BUS_DEVICE(obj), &s->iomem);
}

static void pwr_class_init(ObjectClass *klass, void *data)
{
    DEVICE_CLASS(klass)->reset = pwr_reset;
}

static const TypeInfo pwr_info = {
    .name = TYPE_STM32F4_PWR,
    .parent = TYPE_SYS_BUS_DEVICE,
    .instance_size = sizeof(Stm32f4PwrState),
    .instance_init = pwr_init,
    .class_init = pwr_class_init,
};

static void pwr_register_types(void)
{
    type_register_static(&pwr_info);
}

type_init(pwr_register_types)
