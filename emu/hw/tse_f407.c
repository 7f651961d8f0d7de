/*
 * The tse-f407 machine: the TSE controller board on an STM32F407 (8 MHz crystal), its CAN
 * controller on a QEMU CAN bus (-machine tse-f407,canbus=ID with -object can-bus,id=ID), and
 * the rig (tse_rig.c) wired as docs/board.md's pin map says:
 *   STEP1..6 PC0..5, DIR1..6 PC6..11, ENABLE PC12 (to the rig's inputs);
 *   LIM1..6 PA0..5 and E-STOP PA8 (driven by the rig: a closed NC contact pulls the pin to 0,
 *   an open one lets the pull-up read 1).
 * The image (-kernel ELF) is loaded into the flash at every reset, over what the flash file
 * holds there.
 *
 * SPDX-License-Identifier: GPL-2.0-or-later
 */
#include "qemu/osdep.h"
#include "qapi/error.h"
#include "hw/boards.h"
#include "hw/qdev-properties.h"
#include "hw/arm/boot.h"
#include "net/can_emu.h"
#include "tse_f407_soc.h"

#define TYPE_TSE_F407_MACHINE MACHINE_TYPE_NAME("tse-f407")
OBJECT_DECLARE_SIMPLE_TYPE(TseF407MachineState, TSE_F407_MACHINE)

struct TseF407MachineState {
    MachineState parent_obj;
    CanBusState *canbus;
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
}

static void tse_f407_init(MachineState *machine)
{
    TseF407MachineState *m = TSE_F407_MACHINE(machine);
    DeviceState *dev = qdev_new(TYPE_TSE_F407_SOC);
    object_property_add_child(OBJECT(machine), "soc", OBJECT(dev));
    qdev_prop_set_string(dev, "cpu-type", ARM_CPU_TYPE_NAME("cortex-m4"));
    if (m->canbus) {
        object_property_set_link(OBJECT(dev), "canbus", OBJECT(m->canbus), &error_abort);
    }
    sysbus_realize_and_unref(SYS_BUS_DEVICE(dev), &error_fatal);

    DeviceState *rig = qdev_new(TYPE_TSE_RIG);
    object_property_add_child(OBJECT(machine), "rig", OBJECT(rig));
    sysbus_realize_and_unref(SYS_BUS_DEVICE(rig), &error_fatal);
    wire_rig(TSE_F407_SOC(dev), rig);

    armv7m_load_kernel(ARM_CPU(first_cpu), machine->kernel_filename, 0, 1024 * 1024);
}

static void tse_f407_instance_init(Object *obj)
{
    TseF407MachineState *m = TSE_F407_MACHINE(obj);
    object_property_add_link(obj, "canbus", TYPE_CAN_BUS, (Object **)&m->canbus,
                             object_property_allow_set_link, 0);
    object_property_set_description(obj, "canbus", "the CAN bus CAN1 is on (-object can-bus,id=...)");
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
