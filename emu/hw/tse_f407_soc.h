/*
 * The STM32F407 SoC of the tse-f407 machine: QEMU's Cortex-M4 core (armv7m) and our device
 * models at RM0090's addresses.  The board (tse_f407.c) reaches the ports and the CAN controller
 * through this state to wire the rig and the bus.
 *
 * SPDX-License-Identifier: GPL-2.0-or-later
 */
#ifndef TSE_F407_SOC_H
#define TSE_F407_SOC_H

#include "hw/arm/armv7m.h"
#include "hw/sysbus.h"
#include "net/can_emu.h"
#include "qom/object.h"
#include "tse_f407.h"

OBJECT_DECLARE_SIMPLE_TYPE(TseF407SocState, TSE_F407_SOC)

#define TSE_F407_NUM_GPIO 7  /* A..G: the LQFP144 part's ports (olx_e407 uses F) */
#define TSE_F407_NUM_GATES 20

struct TseF407SocState {
    SysBusDevice parent_obj;

    ARMv7MState armv7m;
    MemoryRegion sram, ccm, bkpsram, flash_alias;
    Clock *refclk;
    DeviceState *rcc, *pwr, *flash, *syscfg, *exti, *iwdg, *can1, *usart1; /* usart1: the boot line's */
    DeviceState *gpio[TSE_F407_NUM_GPIO];
    DeviceState *tim[4]; /* TIM2..TIM5 */
    DeviceState *tim11;
    MemoryRegion gate_off[TSE_F407_NUM_GATES];
    MemoryRegion *gated[TSE_F407_NUM_GATES];
    const char *gate_name[TSE_F407_NUM_GATES];
    bool power_cycle; /* the next reset is a power-on: RAM is lost */

    /* properties */
    char *cpu_type;
    CanBusState *canbus;
    uint32_t bitrate;
    bool wfi_nop;
    uint8_t can_rx_pin, can_tx_pin; /* CAN1's pins: port * 16 + pin (default PB8, PB9) */
    uint8_t boot_usart;             /* the boot line's USART: 1, 2, 3 or 6 (on serial 0) */
    uint32_t app_addr;              /* where the core takes its vector table at reset */
};

/* Re-asserts the core's interrupt request after QEMU's core reset cleared it (wfi-nop): the
 * board registers it as a reset handler after the core's. */
void tse_f407_soc_after_cpu_reset(void *opaque);

#endif
