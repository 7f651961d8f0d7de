/*
 * The tse-f407 machine: the TSE controller board on an STM32F407 (8 MHz crystal), its CAN
 * controller on a QEMU CAN bus, and the rig (tse_rig.c).
 *
 * Machine properties:
 *   can-chardev=ID  the bus bridged to chardev ID (can_host_chardev.c: 16-byte records)
 *   canbus=ID       the bus is -object can-bus,id=ID (e.g. to bridge it with can-host-socketcan
 *                   instead); without it the machine makes its own bus
 *   bitrate=BPS     the bus's bit rate (default 500000): CAN1 takes part only at this rate, and
 *                   the bridge paces the frames it puts on the bus to it
 *
 * The rig is wired as docs/board.md's pin map says:
 *   STEP1..6 PC0..5, DIR1..6 PC6..11, ENABLE PC12 (to the rig's inputs);
 *   LIM1..6 PA0..5 and E-STOP PA8 (driven by the rig: a closed NC contact pulls the pin to 0,
 *   an open one lets the pull-up read 1).
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

struct TseF407MachineState {
    MachineState parent_obj;
    CanBusState *canbus;
    char *can_chardev;
    uint32_t bitrate;
};

enum { PORT_A, PORT_B, PORT_C };

static void wire_rig(TseF407SocState *soc, DeviceState *rig)
{
    for (int k = 0; k < 6; ++k) {
        qdev_connect_gpio_out_named(soc->gpio[PORT_C], GPIO_OUT_PIN, k,
                                    qdev_get_gpio_in_named(rig, RIG_IN_STEP, k));
        qdev_connect_gpio_out_named(soc->gpio[PORT_C], GPIO_OUT_PIN, 6 + k,
                                    qdev_get_gpio_in_named(rig, RIG_IN_DIR, k));
        qdev_connect_gpio_out_named(rig, RIG_OUT_SWITCH, k,
                                    qdev_get_gpio_in_named(soc->gpio[PORT_A], GPIO_IN_EXT, k));
    }
    qdev_connect_gpio_out_named(soc->gpio[PORT_C], GPIO_OUT_PIN, 12,
                                qdev_get_gpio_in_named(rig, RIG_IN_ENABLE, 0));
    qdev_connect_gpio_out_named(rig, RIG_OUT_ESTOP, 0,
                                qdev_get_gpio_in_named(soc->gpio[PORT_A], GPIO_IN_EXT, 8));
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
    sysbus_realize_and_unref(SYS_BUS_DEVICE(dev), &error_fatal);

    DeviceState *rig = qdev_new(TYPE_TSE_RIG);
    object_property_add_child(OBJECT(machine), "rig", OBJECT(rig));
    sysbus_realize_and_unref(SYS_BUS_DEVICE(rig), &error_fatal);
    wire_rig(TSE_F407_SOC(dev), rig);

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
