/*
 * The tse-f407 machine: the TSE controller board on an STM32F407 (any board's pins), its CAN
 * controller on a QEMU CAN bus, and the rig (tse_rig.c).
 *
 * Machine properties:
 *   can-chardev=ID  the bus bridged to chardev ID (can_host_chardev.c: 16-byte records)
 *   canbus=ID       the bus is -object can-bus,id=ID (e.g. to bridge it with can-host-socketcan
 *                   instead); without it the machine makes its own bus
 *   bitrate=BPS     the bus's bit rate (default 500000): CAN1 takes part only at this rate, and
 *                   the bridge paces the frames it puts on the bus to it
 *
 *   step-pins=P:P:P:P:P:P, dir-pins=..., lim-pins=..., enable-pin=P, estop-pin=P, can-pins=RX:TX
 *                   the board's pins, each a port letter and a number ("C0"), as emu/run.sh reads
 *                   them from the image (emu/board_props.py); default docs/board.md's generic map:
 *                   STEP1..6 PC0..5, DIR1..6 PC6..11, ENABLE PC12 (to the rig's inputs), LIM1..6
 *                   PA0..5 and E-STOP PA8 (driven by the rig: a closed NC contact pulls the pin to
 *                   0, an open one lets the pull-up read 1), CAN1 PB8/PB9
 *   boot-usart=N    the boot line's USART (1, 2, 3, 6; default 1)
 *   app-addr=ADDR   where the image's vector table is (default 0x08000000; a board's bootloader
 *                   would jump to e.g. 0x0800C000: the core starts there)
 * The image (-kernel ELF) is loaded into the flash at every reset, over what the flash file
 * holds there.
 *
 * SPDX-License-Identifier: GPL-2.0-or-later
 */
#include "qemu/osdep.h"
#include <sys/prctl.h>
#include "qapi/error.h"
#include "hw/boards.h"
#include "sysemu/reset.h"
#include "hw/qdev-properties.h"
#include "hw/arm/boot.h"
#include "net/can_emu.h"
#include "qom/object_interfaces.h"
#include "tse_f407_soc.h"

#define TYPE_TSE_F407_MACHINE MACHINE_TYPE_NAME("tse-f407")
OBJECT_DECLARE_SIMPLE_TYPE(TseF407MachineState, TSE_F407_MACHINE)

enum { PIN_STEP, PIN_DIR = PIN_STEP + 6, PIN_LIM = PIN_DIR + 6, PIN_ENABLE = PIN_LIM + 6, PIN_ESTOP,
       PIN_CAN_RX, PIN_CAN_TX, NUM_PINS };

struct TseF407MachineState {
    MachineState parent_obj;
    CanBusState *canbus;
    char *can_chardev;
    uint32_t bitrate;
    uint32_t boot_usart;
    uint32_t app_addr;
    uint8_t pin[NUM_PINS]; /* port * 16 + pin */
};

/* "C0:C1:..." (n pins) into pin[first..], or an error naming the property. */
static void parse_pins(TseF407MachineState *m, const char *prop, const char *value, int first, int n,
                       Error **errp)
{
    const char *p = value;
    for (int i = 0; i < n; ++i) {
        char *end;
        const char port = *p;
        if (port < 'A' || port >= 'A' + TSE_F407_NUM_GPIO) {
            error_setg(errp, "tse-f407: %s '%s': pin %d is not on ports A..G", prop, value, i + 1);
            return;
        }
        const long pin = strtol(p + 1, &end, 10);
        if (end == p + 1 || pin < 0 || pin > 15 || (i < n - 1 ? *end != ':' : *end != 0)) {
            error_setg(errp, "tse-f407: %s '%s': expected %d pins such as C0, separated by ':'", prop, value, n);
            return;
        }
        m->pin[first + i] = (uint8_t)((port - 'A') * 16 + pin);
        p = end + 1;
    }
}

#define PIN_PROP(fn, prop, first, n)                                                  \
    static void fn(Object *obj, const char *value, Error **errp)                      \
    {                                                                                 \
        parse_pins(TSE_F407_MACHINE(obj), prop, value, first, n, errp);               \
    }
PIN_PROP(set_step_pins, "step-pins", PIN_STEP, 6)
PIN_PROP(set_dir_pins, "dir-pins", PIN_DIR, 6)
PIN_PROP(set_lim_pins, "lim-pins", PIN_LIM, 6)
PIN_PROP(set_enable_pin, "enable-pin", PIN_ENABLE, 1)
PIN_PROP(set_estop_pin, "estop-pin", PIN_ESTOP, 1)
PIN_PROP(set_can_pins, "can-pins", PIN_CAN_RX, 2)

/* A pin's output to one of the rig's inputs; one of the rig's outputs to a pin's input. */
static void pin_to_rig(TseF407SocState *soc, uint8_t pin, DeviceState *rig, const char *in, int n)
{
    qdev_connect_gpio_out_named(soc->gpio[pin / 16], GPIO_OUT_PIN, pin % 16, qdev_get_gpio_in_named(rig, in, n));
}

static void rig_to_pin(DeviceState *rig, const char *out, int n, TseF407SocState *soc, uint8_t pin)
{
    qdev_connect_gpio_out_named(rig, out, n, qdev_get_gpio_in_named(soc->gpio[pin / 16], GPIO_IN_EXT, pin % 16));
}

static void wire_rig(TseF407MachineState *m, TseF407SocState *soc, DeviceState *rig)
{
    for (int k = 0; k < 6; ++k) {
        pin_to_rig(soc, m->pin[PIN_STEP + k], rig, RIG_IN_STEP, k);
        pin_to_rig(soc, m->pin[PIN_DIR + k], rig, RIG_IN_DIR, k);
        rig_to_pin(rig, RIG_OUT_SWITCH, k, soc, m->pin[PIN_LIM + k]);
    }
    pin_to_rig(soc, m->pin[PIN_ENABLE], rig, RIG_IN_ENABLE, 0);
    rig_to_pin(rig, RIG_OUT_ESTOP, 0, soc, m->pin[PIN_ESTOP]);
    qdev_connect_gpio_out_named(rig, RIG_OUT_POWER, 0,
                                qdev_get_gpio_in_named(DEVICE(soc), SOC_IN_POWER, 0));
    qdev_connect_gpio_out_named(rig, RIG_OUT_CANERR, 0,
                                qdev_get_gpio_in_named(soc->can1, BXCAN_IN_BUS_ERROR, 0));
    /* What the rig observes for the figures: frames the controller takes, watchdog reloads. */
    qdev_connect_gpio_out_named(soc->can1, BXCAN_OUT_RX, 0, qdev_get_gpio_in_named(rig, RIG_IN_CAN_RX, 0));
    qdev_connect_gpio_out_named(soc->iwdg, IWDG_OUT_RELOAD, 0, qdev_get_gpio_in_named(rig, RIG_IN_FEED, 0));
    /* The flash's operations, which the rig counts and may cut with a power cycle (`cutflash`). */
    qdev_connect_gpio_out_named(soc->flash, FLASH_OUT_OP, 0, qdev_get_gpio_in_named(rig, RIG_IN_FLASH_OP, 0));
}

static void tse_f407_init(MachineState *machine)
{
    TseF407MachineState *m = TSE_F407_MACHINE(machine);
    prctl(PR_SET_TIMERSLACK, 1UL, 0, 0, 0);
    if (!m->canbus) {
        Object *bus = object_new(TYPE_CAN_BUS);
        object_property_add_child(OBJECT(machine), "canbus0", bus);
        m->canbus = CAN_BUS(bus);
        object_unref(bus);
    }
    if (m->can_chardev) {
        Object *host = object_new(TYPE_CAN_HOST_CHARDEV);
        object_property_set_str(host, "chardev", m->can_chardev, &error_fatal);
        object_property_set_uint(host, "bitrate", m->bitrate, &error_fatal);
        object_property_set_link(host, "canbus", OBJECT(m->canbus), &error_fatal);
        object_property_add_child(OBJECT(machine), "can-host", host);
        user_creatable_complete(USER_CREATABLE(host), &error_fatal);
        object_unref(host);
    }

    DeviceState *dev = qdev_new(TYPE_TSE_F407_SOC);
    object_property_add_child(OBJECT(machine), "soc", OBJECT(dev));
    qdev_prop_set_string(dev, "cpu-type", ARM_CPU_TYPE_NAME("cortex-m4"));
    object_property_set_link(OBJECT(dev), "canbus", OBJECT(m->canbus), &error_abort);
    qdev_prop_set_uint32(dev, "bitrate", m->bitrate);
    qdev_prop_set_uint8(dev, "can-rx-pin", m->pin[PIN_CAN_RX]);
    qdev_prop_set_uint8(dev, "can-tx-pin", m->pin[PIN_CAN_TX]);
    qdev_prop_set_uint8(dev, "boot-usart", (uint8_t)m->boot_usart);
    qdev_prop_set_uint32(dev, "app-addr", m->app_addr);
    sysbus_realize_and_unref(SYS_BUS_DEVICE(dev), &error_fatal);

    DeviceState *rig = qdev_new(TYPE_TSE_RIG);
    object_property_add_child(OBJECT(machine), "rig", OBJECT(rig));
    sysbus_realize_and_unref(SYS_BUS_DEVICE(rig), &error_fatal);
    wire_rig(m, TSE_F407_SOC(dev), rig);

    armv7m_load_kernel(ARM_CPU(first_cpu), machine->kernel_filename, 0, 1024 * 1024);
    qemu_register_reset(tse_f407_soc_after_cpu_reset, dev); /* after the core's (registered above) */
}

static char *get_can_chardev(Object *obj, Error **errp)
{
    return g_strdup(TSE_F407_MACHINE(obj)->can_chardev);
}

static void set_can_chardev(Object *obj, const char *value, Error **errp)
{
    TseF407MachineState *m = TSE_F407_MACHINE(obj);
    g_free(m->can_chardev);
    m->can_chardev = g_strdup(value);
}

static void tse_f407_instance_init(Object *obj)
{
    TseF407MachineState *m = TSE_F407_MACHINE(obj);
    object_property_add_link(obj, "canbus", TYPE_CAN_BUS, (Object **)&m->canbus,
                             object_property_allow_set_link, 0);
    object_property_set_description(obj, "canbus", "the CAN bus CAN1 is on (-object can-bus,id=...)");
    object_property_add_str(obj, "can-chardev", get_can_chardev, set_can_chardev);
    object_property_set_description(obj, "can-chardev", "the chardev the bus is bridged to (16-byte records)");
    object_property_add_uint32_ptr(obj, "bitrate", &m->bitrate, OBJ_PROP_FLAG_READWRITE);
    object_property_set_description(obj, "bitrate", "the bus's bit rate (bit/s)");
    m->bitrate = 500000;
    static const struct { const char *name; void (*set)(Object *, const char *, Error **); const char *what; } pins[] = {
        {"step-pins", set_step_pins, "STEP1..6, e.g. C0:C1:C2:C3:C4:C5"},
        {"dir-pins", set_dir_pins, "DIR1..6"},
        {"lim-pins", set_lim_pins, "LIM1..6, the rig's switches"},
        {"enable-pin", set_enable_pin, "ENABLE (the rig's drivers)"},
        {"estop-pin", set_estop_pin, "E-STOP (the rig's chain)"},
        {"can-pins", set_can_pins, "CAN1 RX:TX"},
    };
    for (size_t i = 0; i < ARRAY_SIZE(pins); ++i) {
        object_property_add_str(obj, pins[i].name, NULL, pins[i].set);
        object_property_set_description(obj, pins[i].name, pins[i].what);
    }
    object_property_add_uint32_ptr(obj, "boot-usart", &m->boot_usart, OBJ_PROP_FLAG_READWRITE);
    object_property_set_description(obj, "boot-usart", "the boot line's USART (1, 2, 3, 6)");
    object_property_add_uint32_ptr(obj, "app-addr", &m->app_addr, OBJ_PROP_FLAG_READWRITE);
    object_property_set_description(obj, "app-addr", "the image's vector table (a bootloader's jump)");
    m->boot_usart = 1;
    m->app_addr = 0x08000000;
    /* docs/board.md's generic map */
    static const uint8_t generic[NUM_PINS] = {
        32, 33, 34, 35, 36, 37,       /* STEP PC0..5 */
        38, 39, 40, 41, 42, 43,       /* DIR PC6..11 */
        0, 1, 2, 3, 4, 5,             /* LIM PA0..5 */
        44, 8, 24, 25,                /* ENABLE PC12, E-STOP PA8, CAN PB8/PB9 */
    };
    memcpy(m->pin, generic, sizeof generic);
}

static void tse_f407_class_init(ObjectClass *oc, void *data)
{
    MachineClass *mc = MACHINE_CLASS(oc);
    mc->desc = "TSE controller board: STM32F407 (Cortex-M4), CAN1 on a CAN bus, the slide rig";
    mc->init = tse_f407_init;
    mc->default_cpu_type = ARM_CPU_TYPE_NAME("cortex-m4");
    mc->min_cpus = mc->max_cpus = mc->default_cpus = 1;
}

static const TypeInfo tse_f407_info = {
    .name = TYPE_TSE_F407_MACHINE,
    .parent = TYPE_MACHINE,
    .instance_size = sizeof(TseF407MachineState),
    .instance_init = tse_f407_instance_init,
    .class_init = tse_f407_class_init,
};

static void tse_f407_register_types(void)
{
    type_register_static(&tse_f407_info);
}

type_init(tse_f407_register_types)
