/*
 * The STM32F407 SoC of the tse-f407 machine (RM0090 memory map, section 2.3; interrupt vector
 * table 61).
 *
 * Memory: 1 MiB flash at 0x08000000 (aliased at 0, as when booting from flash), 128 KiB SRAM
 * (SRAM1 and SRAM2) at 0x20000000, 64 KiB CCM data RAM at 0x10000000, 4 KiB backup SRAM at
 * 0x40024000; anything else outside the peripherals below is a bus fault, as on the part.
 * RAM keeps its contents over a system reset (watchdog, software, NRST) and is cleared by a
 * power cycle (the "power-cycle" input, which the rig's `reset` pulses).
 *
 * Peripherals: our RCC, PWR, FLASH, GPIOA..G, SYSCFG, EXTI, TIM2..5, TIM11 (its channel 1 on
 * HSE_RTC: the image measures its crystal with it), IWDG and bxCAN1 (on the pins can-rx-pin,
 * can-tx-pin: PB8/PB9 by default); QEMU's stm32f2xx USART as the boot line's USART (boot-usart:
 * 1, 2, 3 or 6; serial 0).  The core starts from the vector table at app-addr (0x08000000, or
 * where a board's bootloader would jump: the flash below it is left as the flash file has it).  The others are QEMU's "unimplemented devices"
 * (read 0, writes ignored, logged with -d unimp).  A peripheral whose RCC enable bit is clear
 * reads 0 and ignores writes (its registers are switched off; a guest error is logged).
 *
 * SPDX-License-Identifier: GPL-2.0-or-later
 */
#include "qemu/osdep.h"
#include "qemu/log.h"
#include "qemu/units.h"
#include "qapi/error.h"
#include "exec/address-spaces.h"
#include "hw/irq.h"
#include "hw/qdev-clock.h"
#include "hw/qdev-properties.h"
#include "hw/misc/unimp.h"
#include "hw/char/stm32f2xx_usart.h"
#include "sysemu/sysemu.h"
#include "hw/core/cpu.h"
#include "tse_f407_soc.h"

#define FLASH_BASE 0x08000000
#define SRAM_BASE 0x20000000
#define SRAM_SIZE (128 * KiB)
#define CCM_BASE 0x10000000
#define CCM_SIZE (64 * KiB)
#define BKPSRAM_BASE 0x40024000
#define BKPSRAM_SIZE (4 * KiB)

#define IRQ_FLASH 4
#define IRQ_CAN1_TX 19
#define IRQ_TIM11 26 /* TIM1_TRG_COM_TIM11 */
#define TIM11_ADDR 0x40014800
static const hwaddr gpio_addr[TSE_F407_NUM_GPIO] = {
    0x40020000, 0x40020400, 0x40020800, 0x40020C00, 0x40021000, 0x40021400, 0x40021800,
};
/* The boot line's USART (RM0090 table 1 and 61): address, clock enable (APB1 or APB2 and bit),
 * interrupt. */
static const struct {
    uint8_t n;
    hwaddr addr;
    const char *group;
    int bit, irq;
    const char *name;
} usarts[] = {
    {1, 0x40011000, RCC_GPIO_APB2EN, 4, 37, "USART1"},
    {2, 0x40004400, RCC_GPIO_APB1EN, 17, 38, "USART2"},
    {3, 0x40004800, RCC_GPIO_APB1EN, 18, 39, "USART3"},
    {6, 0x40011400, RCC_GPIO_APB2EN, 5, 71, "USART6"},
};
static const hwaddr tim_addr[4] = { 0x40000000, 0x40000400, 0x40000800, 0x40000C00 };
static const int tim_irq[4] = { 28, 29, 30, 50 };
static const int exti_irq[EXTI_NUM_IRQS] = { 6, 7, 8, 9, 10, 23, 40, 1, 41, 42, 62, 76, 2, 3 };

/* ---- clock gates ---- */

static uint64_t gate_off_read(void *opaque, hwaddr addr, unsigned size)
{
    qemu_log_mask(LOG_GUEST_ERROR, "tse-f407: read of %s+0x%" HWADDR_PRIx
                  " with its RCC clock enable off: 0\n", (const char *)opaque, addr);
    return 0;
}

static void gate_off_write(void *opaque, hwaddr addr, uint64_t val, unsigned size)
{
    qemu_log_mask(LOG_GUEST_ERROR, "tse-f407: write of %s+0x%" HWADDR_PRIx
                  " with its RCC clock enable off: ignored\n", (const char *)opaque, addr);
}

static const MemoryRegionOps gate_off_ops = {
    .read = gate_off_read,
    .write = gate_off_write,
    .endianness = DEVICE_LITTLE_ENDIAN,
};

static void gate_in(void *opaque, int n, int level)
{
    TseF407SocState *s = opaque;
    if (s->gated[n]) {
        memory_region_set_enabled(s->gated[n], level != 0);
    }
}

/* Maps dev's registers at addr behind RCC enable line `line` of the given group. */
static void map_gated(TseF407SocState *s, int gate, const char *name, DeviceState *dev,
                      hwaddr addr, const char *rcc_group, int line)
{
    MemoryRegion *mr = sysbus_mmio_get_region(SYS_BUS_DEVICE(dev), 0);
    s->gate_name[gate] = name;
    s->gated[gate] = mr;
    memory_region_init_io(&s->gate_off[gate], OBJECT(s), &gate_off_ops, (void *)name, name,
                          memory_region_size(mr));
    memory_region_add_subregion_overlap(get_system_memory(), addr, &s->gate_off[gate], -1);
    memory_region_add_subregion(get_system_memory(), addr, mr);
    memory_region_set_enabled(mr, false);
    qdev_connect_gpio_out_named(s->rcc, rcc_group, line,
                                qdev_get_gpio_in_named(DEVICE(s), "gate", gate));
}

/* ---- the core's interrupt line ---- */

/*
 * With wfi-nop (the default) the core never sleeps: its interrupt request stays asserted, so WFI
 * finds "work" and returns at once (the architecture allows WFI to be a no-op; whether an
 * exception is taken is still the NVIC's decision, asked at every new request).  QEMU wakes a
 * sleeping core through its main loop thread, two thread hand-overs an interrupt: at the
 * firmware's 200 kHz step interrupt that holds virtual time to about a tenth of real time,
 * whereas a core that never sleeps takes its timers in its own thread (icount) and runs ahead
 * of real time, which -icount align=on then paces.
 */
static void core_irq_in(void *opaque, int n, int level)
{
    TseF407SocState *s = opaque;
    CPUState *cs = CPU(s->armv7m.cpu);
    if (level || s->wfi_nop) {
        cpu_interrupt(cs, CPU_INTERRUPT_HARD);
    } else {
        cpu_reset_interrupt(cs, CPU_INTERRUPT_HARD);
    }
}

void tse_f407_soc_after_cpu_reset(void *opaque)
{
    TseF407SocState *s = opaque;
    if (s->wfi_nop) {
        cpu_interrupt(CPU(s->armv7m.cpu), CPU_INTERRUPT_HARD);
    }
}

/* ---- power cycle ---- */

static void power_cycle_in(void *opaque, int n, int level)
{
    TseF407SocState *s = opaque;
    if (level) {
        s->power_cycle = true;
        qemu_irq_pulse(qdev_get_gpio_in_named(s->rcc, RCC_GPIO_RESET, RCC_RESET_POWER_ON));
    }
}

static void soc_reset(DeviceState *dev)
{
    TseF407SocState *s = TSE_F407_SOC(dev);
    if (s->power_cycle) {
        memset(memory_region_get_ram_ptr(&s->sram), 0, SRAM_SIZE);
        memset(memory_region_get_ram_ptr(&s->ccm), 0, CCM_SIZE);
        memset(memory_region_get_ram_ptr(&s->bkpsram), 0, BKPSRAM_SIZE);
        s->power_cycle = false;
    }
}

/* ---- construction ---- */

static DeviceState *add(TseF407SocState *s, const char *type, hwaddr addr, Error **errp)
{
    DeviceState *dev = qdev_new(type);
    object_property_add_child(OBJECT(s), type, OBJECT(dev));
    if (!sysbus_realize_and_unref(SYS_BUS_DEVICE(dev), errp)) {
        return NULL;
    }
    if (addr) {
        sysbus_mmio_map(SYS_BUS_DEVICE(dev), 0, addr);
    }
    return dev;
}

static qemu_irq nvic(TseF407SocState *s, int n)
{
    return qdev_get_gpio_in(DEVICE(&s->armv7m), n);
}

static bool make_memory(TseF407SocState *s, Error **errp)
{
    MemoryRegion *sys = get_system_memory();
    Object *o = OBJECT(s);

    s->flash = qdev_new(TYPE_STM32F4_FLASH);
    object_property_add_child(o, "flash", OBJECT(s->flash));
    qdev_connect_clock_in(s->flash, "hclk", qdev_get_clock_out(s->rcc, RCC_CLK_HCLK));
    if (!sysbus_realize_and_unref(SYS_BUS_DEVICE(s->flash), errp)) {
        return false;
    }
    sysbus_mmio_map(SYS_BUS_DEVICE(s->flash), 0, 0x40023C00);
    MemoryRegion *array = sysbus_mmio_get_region(SYS_BUS_DEVICE(s->flash), 1);
    memory_region_add_subregion(sys, FLASH_BASE, array);
    memory_region_init_alias(&s->flash_alias, o, "flash.alias", array, 0, memory_region_size(array));
    memory_region_add_subregion(sys, 0, &s->flash_alias);

    memory_region_init_ram(&s->sram, o, "sram", SRAM_SIZE, &error_fatal);
    memory_region_init_ram(&s->ccm, o, "ccm", CCM_SIZE, &error_fatal);
    memory_region_init_ram(&s->bkpsram, o, "bkpsram", BKPSRAM_SIZE, &error_fatal);
    memory_region_add_subregion(sys, SRAM_BASE, &s->sram);
    memory_region_add_subregion(sys, CCM_BASE, &s->ccm);
    memory_region_add_subregion(sys, BKPSRAM_BASE, &s->bkpsram);
    return true;
}

static bool make_core(TseF407SocState *s, Error **errp)
{
    DeviceState *armv7m = DEVICE(&s->armv7m);
    Clock *hclk = qdev_get_clock_out(s->rcc, RCC_CLK_HCLK);

    /* SysTick's external reference is HCLK / 8 (RM0090 figure 21). */
    clock_set_mul_div(s->refclk, 8, 1);
    clock_set_source(s->refclk, hclk);
    qdev_prop_set_uint32(armv7m, "num-irq", 82);
    qdev_prop_set_string(armv7m, "cpu-type", s->cpu_type);
    qdev_prop_set_bit(armv7m, "enable-bitband", true);
    /* An image linked behind a bootloader (monster8: 0x0800C000) starts as that bootloader's
     * jump starts it: SP and PC from its own vector table, VTOR there (a core without the
     * Security Extension takes the non-secure reset VTOR). */
    qdev_prop_set_uint32(armv7m, "init-svtor", s->app_addr);
    qdev_prop_set_uint32(armv7m, "init-nsvtor", s->app_addr);
    qdev_connect_clock_in(armv7m, "cpuclk", hclk);
    qdev_connect_clock_in(armv7m, "refclk", s->refclk);
    object_property_set_link(OBJECT(&s->armv7m), "memory", OBJECT(get_system_memory()), &error_abort);
    if (!sysbus_realize(SYS_BUS_DEVICE(&s->armv7m), errp)) {
        return false;
    }
    qdev_connect_gpio_out_named(armv7m, "SYSRESETREQ", 0,
                                qdev_get_gpio_in_named(s->rcc, RCC_GPIO_RESET, RCC_RESET_SOFTWARE));
    /* The NVIC's interrupt line to the core passes through core_irq (see there). */
    sysbus_connect_irq(SYS_BUS_DEVICE(&s->armv7m.nvic), 0, qdev_get_gpio_in_named(DEVICE(s), "core-irq", 0));
    return true;
}

static bool make_peripherals(TseF407SocState *s, Error **errp)
{
    int gate = 0;

    sysbus_connect_irq(SYS_BUS_DEVICE(s->flash), 0, nvic(s, IRQ_FLASH));

    if (!(s->pwr = add(s, TYPE_STM32F4_PWR, 0, errp))) {
        return false;
    }
    map_gated(s, gate++, "PWR", s->pwr, 0x40007000, RCC_GPIO_APB1EN, 28);

    if (!(s->exti = add(s, TYPE_STM32F4_EXTI, 0x40013C00, errp))) {
        return false;
    }
    for (int i = 0; i < EXTI_NUM_IRQS; ++i) {
        sysbus_connect_irq(SYS_BUS_DEVICE(s->exti), i, nvic(s, exti_irq[i]));
    }
    if (!(s->syscfg = add(s, TYPE_STM32F4_SYSCFG, 0, errp))) {
        return false;
    }
    map_gated(s, gate++, "SYSCFG", s->syscfg, 0x40013800, RCC_GPIO_APB2EN, 14);
    for (int i = 0; i < 16; ++i) {
        qdev_connect_gpio_out(s->syscfg, i, qdev_get_gpio_in_named(s->exti, EXTI_IN_LINE, i));
    }

    static const char *const port_name[TSE_F407_NUM_GPIO] = {"GPIOA", "GPIOB", "GPIOC", "GPIOD", "GPIOE",
                                                              "GPIOF", "GPIOG"};
    for (int p = 0; p < TSE_F407_NUM_GPIO; ++p) {
        s->gpio[p] = qdev_new(TYPE_STM32F4_GPIO);
        object_property_add_child(OBJECT(s), port_name[p], OBJECT(s->gpio[p]));
        qdev_prop_set_uint8(s->gpio[p], "port", p);
        if (!sysbus_realize_and_unref(SYS_BUS_DEVICE(s->gpio[p]), errp)) {
            return false;
        }
        map_gated(s, gate++, port_name[p], s->gpio[p], gpio_addr[p], RCC_GPIO_AHB1EN, p);
        for (int pin = 0; pin < 16; ++pin) {
            qdev_connect_gpio_out_named(s->gpio[p], GPIO_OUT_EXTI, pin,
                                        qdev_get_gpio_in(s->syscfg, 16 * p + pin));
        }
    }

    static const char *const tim_name[4] = {"TIM2", "TIM3", "TIM4", "TIM5"};
    for (int t = 0; t < 4; ++t) {
        s->tim[t] = qdev_new(TYPE_STM32F4_TIM);
        object_property_add_child(OBJECT(s), tim_name[t], OBJECT(s->tim[t]));
        qdev_prop_set_uint32(s->tim[t], "width", t == 0 || t == 3 ? 32 : 16);
        qdev_connect_clock_in(s->tim[t], "clk", qdev_get_clock_out(s->rcc, RCC_CLK_TIMCLK1));
        if (!sysbus_realize_and_unref(SYS_BUS_DEVICE(s->tim[t]), errp)) {
            return false;
        }
        map_gated(s, gate++, tim_name[t], s->tim[t], tim_addr[t], RCC_GPIO_APB1EN, t);
        sysbus_connect_irq(SYS_BUS_DEVICE(s->tim[t]), 0, nvic(s, tim_irq[t]));
    }

    /* TIM11: 16 bits on the APB2 timer clock; TI1 remapped (OR[1:0] = 2) to HSE_RTC. */
    s->tim11 = qdev_new(TYPE_STM32F4_TIM);
    object_property_add_child(OBJECT(s), "TIM11", OBJECT(s->tim11));
    qdev_prop_set_uint32(s->tim11, "width", 16);
    qdev_prop_set_uint32(s->tim11, "ti1-rmp", 2);
    qdev_connect_clock_in(s->tim11, "clk", qdev_get_clock_out(s->rcc, RCC_CLK_TIMCLK2));
    qdev_connect_clock_in(s->tim11, "ti1", qdev_get_clock_out(s->rcc, RCC_CLK_HSE_RTC));
    if (!sysbus_realize_and_unref(SYS_BUS_DEVICE(s->tim11), errp)) {
        return false;
    }
    map_gated(s, gate++, "TIM11", s->tim11, TIM11_ADDR, RCC_GPIO_APB2EN, 18);
    sysbus_connect_irq(SYS_BUS_DEVICE(s->tim11), 0, nvic(s, IRQ_TIM11));

    if (!(s->iwdg = add(s, TYPE_STM32F4_IWDG, 0x40003000, errp))) {
        return false;
    }
    qdev_connect_gpio_out_named(s->iwdg, IWDG_OUT_RESET, 0,
                                qdev_get_gpio_in_named(s->rcc, RCC_GPIO_RESET, RCC_RESET_IWDG));

    s->can1 = qdev_new(TYPE_STM32F4_BXCAN);
    object_property_add_child(OBJECT(s), "CAN1", OBJECT(s->can1));
    if (s->canbus) {
        object_property_set_link(OBJECT(s->can1), "canbus", OBJECT(s->canbus), &error_abort);
    }
    qdev_prop_set_uint32(s->can1, "bus-bitrate", s->bitrate);
    qdev_connect_clock_in(s->can1, "pclk", qdev_get_clock_out(s->rcc, RCC_CLK_PCLK1));
    if (!sysbus_realize_and_unref(SYS_BUS_DEVICE(s->can1), errp)) {
        return false;
    }
    map_gated(s, gate++, "CAN1", s->can1, 0x40006400, RCC_GPIO_APB1EN, 25);
    for (int i = 0; i < 4; ++i) {
        sysbus_connect_irq(SYS_BUS_DEVICE(s->can1), i, nvic(s, IRQ_CAN1_TX + i));
    }
    const uint8_t can_pin[2] = {s->can_rx_pin, s->can_tx_pin};
    for (int i = 0; i < 2; ++i) {
        if (can_pin[i] / 16 >= TSE_F407_NUM_GPIO) {
            error_setg(errp, "tse-f407: CAN pin %u is not on ports A..G", (unsigned)can_pin[i]);
            return false;
        }
    }
    qdev_connect_gpio_out_named(s->gpio[s->can_rx_pin / 16], GPIO_OUT_AF, s->can_rx_pin % 16,
                                qdev_get_gpio_in_named(s->can1, BXCAN_IN_RX_AF, 0));
    qdev_connect_gpio_out_named(s->gpio[s->can_tx_pin / 16], GPIO_OUT_AF, s->can_tx_pin % 16,
                                qdev_get_gpio_in_named(s->can1, BXCAN_IN_TX_AF, 0));

    int u = -1;
    for (int i = 0; i < (int)ARRAY_SIZE(usarts); ++i) {
        if (usarts[i].n == s->boot_usart) {
            u = i;
        }
    }
    if (u < 0) {
        error_setg(errp, "tse-f407: boot-usart %u: not 1, 2, 3 or 6", (unsigned)s->boot_usart);
        return false;
    }
    s->usart1 = qdev_new(TYPE_STM32F2XX_USART);
    object_property_add_child(OBJECT(s), usarts[u].name, OBJECT(s->usart1));
    qdev_prop_set_chr(s->usart1, "chardev", serial_hd(0));
    if (!sysbus_realize_and_unref(SYS_BUS_DEVICE(s->usart1), errp)) {
        return false;
    }
    map_gated(s, gate++, usarts[u].name, s->usart1, usarts[u].addr, usarts[u].group, usarts[u].bit);
    sysbus_connect_irq(SYS_BUS_DEVICE(s->usart1), 0, nvic(s, usarts[u].irq));
    assert(gate <= TSE_F407_NUM_GATES);
    return true;
}

static void make_unimplemented(TseF407SocState *s)
{
    static const struct { const char *name; hwaddr addr, size; } u[] = {
        {"TIM6", 0x40001000, 0x400}, {"TIM7", 0x40001400, 0x400}, {"TIM12", 0x40001800, 0x400},
        {"TIM13", 0x40001C00, 0x400}, {"TIM14", 0x40002000, 0x400}, {"RTC/BKP", 0x40002800, 0x400},
        {"WWDG", 0x40002C00, 0x400}, {"I2S2ext", 0x40003400, 0x400}, {"SPI2", 0x40003800, 0x400},
        {"SPI3", 0x40003C00, 0x400}, {"I2S3ext", 0x40004000, 0x400}, {"USART2", 0x40004400, 0x400},
        {"USART3", 0x40004800, 0x400}, {"UART4", 0x40004C00, 0x400}, {"UART5", 0x40005000, 0x400},
        {"I2C1", 0x40005400, 0x400}, {"I2C2", 0x40005800, 0x400}, {"I2C3", 0x40005C00, 0x400},
        {"CAN2", 0x40006800, 0x400}, {"DAC", 0x40007400, 0x400}, {"TIM1", 0x40010000, 0x400},
        {"TIM8", 0x40010400, 0x400}, {"USART6", 0x40011400, 0x400}, {"ADC", 0x40012000, 0x400},
        {"SDIO", 0x40012C00, 0x400}, {"SPI1", 0x40013000, 0x400}, {"TIM9", 0x40014000, 0x400},
        {"TIM10", 0x40014400, 0x400},
        {"GPIOH", 0x40021C00, 0x400}, {"GPIOI", 0x40022000, 0x400},
        {"CRC", 0x40023000, 0x400}, {"DMA1", 0x40026000, 0x400}, {"DMA2", 0x40026400, 0x400},
        {"ETH", 0x40028000, 0x1400}, {"OTG_HS", 0x40040000, 0x40000}, {"OTG_FS", 0x50000000, 0x40000},
        {"DCMI", 0x50050000, 0x400}, {"RNG", 0x50060800, 0x400}, {"FSMC", 0xA0000000, 0x1000},
    };
    for (size_t i = 0; i < ARRAY_SIZE(u); ++i) {
        if (strcmp(u[i].name, object_get_canonical_path_component(OBJECT(s->usart1))) != 0) {
            create_unimplemented_device(u[i].name, u[i].addr, u[i].size); /* not the boot line's */
        }
    }
}

static void soc_realize(DeviceState *dev, Error **errp)
{
    TseF407SocState *s = TSE_F407_SOC(dev);

    if (!(s->rcc = add(s, TYPE_STM32F4_RCC, 0x40023800, errp))) {
        return;
    }
    if (!make_memory(s, errp) || !make_core(s, errp) || !make_peripherals(s, errp)) {
        return;
    }
    make_unimplemented(s);
}

static void soc_init(Object *obj)
{
    TseF407SocState *s = TSE_F407_SOC(obj);
    object_initialize_child(obj, "armv7m", &s->armv7m, TYPE_ARMV7M);
    s->refclk = qdev_init_clock_in(DEVICE(obj), "refclk", NULL, NULL, 0);
    qdev_init_gpio_in_named(DEVICE(obj), gate_in, "gate", TSE_F407_NUM_GATES);
    qdev_init_gpio_in_named(DEVICE(obj), power_cycle_in, SOC_IN_POWER, 1);
    qdev_init_gpio_in_named(DEVICE(obj), core_irq_in, "core-irq", 1);
}

static Property soc_properties[] = {
    DEFINE_PROP_STRING("cpu-type", TseF407SocState, cpu_type),
    DEFINE_PROP_LINK("canbus", TseF407SocState, canbus, TYPE_CAN_BUS, CanBusState *),
    DEFINE_PROP_UINT32("bitrate", TseF407SocState, bitrate, 500000),
    DEFINE_PROP_BOOL("wfi-nop", TseF407SocState, wfi_nop, true),
    DEFINE_PROP_UINT8("can-rx-pin", TseF407SocState, can_rx_pin, 1 * 16 + 8),
    DEFINE_PROP_UINT8("can-tx-pin", TseF407SocState, can_tx_pin, 1 * 16 + 9),
    DEFINE_PROP_UINT8("boot-usart", TseF407SocState, boot_usart, 1),
    DEFINE_PROP_UINT32("app-addr", TseF407SocState, app_addr, 0x08000000),
    DEFINE_PROP_END_OF_LIST(),
};

static void soc_class_init(ObjectClass *klass, void *data)
{
    DeviceClass *dc = DEVICE_CLASS(klass);
    dc->realize = soc_realize;
    dc->reset = soc_reset;
    device_class_set_props(dc, soc_properties);
}

static const TypeInfo soc_info = {
    .name = TYPE_TSE_F407_SOC,
    .parent = TYPE_SYS_BUS_DEVICE,
    .instance_size = sizeof(TseF407SocState),
    .instance_init = soc_init,
    .class_init = soc_class_init,
};

static void soc_register_types(void)
{
    type_register_static(&soc_info);
}

type_init(soc_register_types)
