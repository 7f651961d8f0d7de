/* The board's bootloader (docs/protocol.md, Updating the firmware): sector 0 of the flash.
 *
 * At reset, before it touches a clock or a pin: an update request from the application (BOOT_ENTER,
 * boot_f4.h) means stay; otherwise a whole image for this board in the application area
 * (boot/decide.h) is started at once, with every peripheral as reset left it, which is what the
 * application's start-up expects.  Staying: the clocks, the pins in their safe state (drivers
 * disabled), CAN at the application's node and bit rate (500 kbit/s and TSE_BOARD_NODE without a
 * request), and the update's commands (boot/bus.h) until BOOT_START, which resets the board so that
 * the decision above starts the new image.  The watchdog, which an application may have started
 * and no reset stops, is fed throughout (the erase feeds it from RAM). */
#include <stdint.h>

#include "boot/bus.h"
#include "boot/decide.h"
#include "boot_f4.h"
#include "hal_stm32f4/board_io.h"
#include "hal_stm32f4/bxcan.h"
#include "hal_stm32f4/clock.h"
#include "hal_stm32f4/flash_f4.h"
#include "hal_stm32f4/iwdg.h"
#include "hal_stm32f4/pinmap.h"
#include "hal_stm32f4/regs_core.h"

#ifndef TSE_BOARD_NODE
#define TSE_BOARD_NODE 1
#endif
#define FLASH_BASE 0x08000000u
#define DEFAULT_KBPS 500u

static bxcan_dev can;
static boot_layout layout;
static boot_bus bus;
static flash_ops ops;

void CAN1_RX0_IRQHandler(void);
void CAN1_TX_IRQHandler(void);
void CAN1_SCE_IRQHandler(void);

void CAN1_RX0_IRQHandler(void)
{
    bxcan_rx0_isr(&can);
}

void CAN1_TX_IRQHandler(void)
{
    bxcan_tx_isr(&can);
}

void CAN1_SCE_IRQHandler(void)
{
    bxcan_sce_isr(&can);
}

__attribute__((noreturn)) static void reset(void)
{
    __asm__ volatile("dsb" ::: "memory");
    TSE_SCB->AIRCR = SCB_AIRCR_VECTKEY | SCB_AIRCR_SYSRESETREQ;
    for (;;)
        __asm__ volatile("nop");
}

/* The application's vector table at app: its stack pointer, then its reset handler. */
__attribute__((noreturn)) static void start(uint32_t app)
{
    const volatile uint32_t *v = (const volatile uint32_t *)app;
    TSE_SCB->VTOR = app;
    __asm__ volatile("msr msp, %0\n\t"
                     "bx %1\n" ::"r"(v[0]),
                     "r"(v[1])
                     : "memory");
    for (;;)
        __asm__ volatile("nop");
}

static void feed(void)
{
    board_iwdg_feed();
}

int main(void)
{
    boot_layout_stm32f4(&layout, BOOT_F4_BOOT_SECTORS, BOOT_F4_APP_END_SECTOR);
    const uint32_t board = boot_board_id(TSE_BOARD_NAME);
    uint8_t node = TSE_BOARD_NODE;
    uint32_t kbps = DEFAULT_KBPS;
    feed();
    if (!boot_request_take(BOOT_F4_REQUEST, &node, &kbps)) {
        boot_image_status why;
        boot_image_header h;
        if (boot_decide(&layout, (const uint8_t *)FLASH_BASE, board, false, &why, &h) == BOOT_START_APP)
            start(FLASH_BASE + layout.app_offset);
    }
    const board_clocks clocks = board_clock_init();
    board_clock_enable_peripherals();
    board_pins_init();
    ops = flash_f4_device_ops(flash_f4_feed_iwdg, layout.sectors[0].number,
                              layout.sectors[layout.nsectors - 1u].number + 1u);
    const bxcan_status st = bxcan_init(&can, TSE_CAN1, clocks.apb1_hz, kbps * 1000u, node, feed);
    if (st == BXCAN_OK || st == BXCAN_ERR_LEAVE_INIT) {
        tse_nvic_enable(IRQ_CAN1_RX0, PRIO_CAN);
        tse_nvic_enable(IRQ_CAN1_TX, PRIO_CAN);
        tse_nvic_enable(IRQ_CAN1_SCE, PRIO_CAN);
    }
    const hal_can hc = bxcan_hal(&can);
    boot_bus_init(&bus, &layout, &ops, board, node, hc);
    for (;;) {
        feed();
        hal_can_frame f;
        while (hc.receive(hc.ctx, &f) == 1)
            boot_bus_frame(&bus, &f);
        if (bus.start) {
            /* BOOT_START's ACK out first (a few frame times), then a reset starts the image. */
            for (uint32_t i = 0; i < 2000000u && can_ring_count(&can.tx) != 0; ++i)
                feed();
            for (volatile uint32_t i = 0; i < 200000u; ++i) {
            }
            reset();
        }
    }
}
