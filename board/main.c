/* tse-fw: the controller firmware on its board (STM32F405/407).
 *
 * The same firmware as the simulator (host_tools/tse_sim), on hal/stm32f4, in the contexts of
 * fw/runtime.h: start-up faults are recorded and reported rather than hung on; the step interrupt
 * (TIM2) runs the step generator; the control interrupt (TIM3, below it, above CAN) runs each
 * control tick - supervision, what the thread handed over, the next segment - and feeds the
 * watchdog; the main loop is the controller's thread - frames in and out, planning, validation;
 * the e-stop input interrupts whatever runs and halts stepping itself.  What passes between the
 * thread and the tick passes through the firmware's hand-over, which needs no lock. */
#include <string.h>

#include "boot_f4.h"
#include "fw/controller.h"
#include "fw/limits.h"
#include "fw/proto_wire.h"
#include "fw/runtime.h"
#include "hal_stm32f4/board_io.h"
#include "hal_stm32f4/bootline.h"
#include "hal_stm32f4/bxcan.h"
#include "hal_stm32f4/clock.h"
#include "hal_stm32f4/fault.h"
#include "hal_stm32f4/flash_f4.h"
#include "hal_stm32f4/iwdg.h"
#include "hal_stm32f4/param_log.h"
#include "hal_stm32f4/pinmap.h"
#include "hal_stm32f4/regs_can.h"
#include "hal_stm32f4/regs_core.h"

/* The board's name in BOARD (INFO_GET page 1), from board/CMakeLists.txt. */
#ifndef TSE_BOARD_NAME
#error "TSE_BOARD_NAME: the board's name, given by board/CMakeLists.txt"
#endif
_Static_assert(sizeof TSE_BOARD_NAME - 1u <= 8u, "TSE_BOARD_NAME: BOARD carries 8 characters at most");

/* The board's rates, the built-in ones (fw/limits.h); the controller reports them in INFO, and
 * tsectl and tse.can judge its paths and sets at what it reports. */
#define CONTROL_HZ FW_SEGMENT_HZ
#define STEP_HZ FW_STEP_HZ
/* The control tick feeds the watchdog while the thread proves progress (fw_thread_progress: every
 * poll, every few pieces of a validation), so a stuck tick or a stuck main loop lets it bite; a
 * parameter save's sector erase feeds it itself. */
#define WATCHDOG_MS 2000u

/* A host streaming a trajectory may have PROTO_TRAJ_WINDOW rows of four frames in flight: they
 * must fit the receive ring with room to spare while the main loop validates a row. */
_Static_assert(4u * PROTO_TRAJ_WINDOW <= CAN_RING_CAPACITY / 2u, "trajectory window: half the receive ring");

/* Everything the board holds, in one place a debugger (and the boot test) can read. */
typedef struct {
    fw_controller_mem fw_mem;
    fw_controller *fw;           /* in fw_mem */
    board_ticker ticker;
    bxcan_dev can;
    param_log store;
    board_clocks clocks;
    board_fault_record previous; /* the fault that ended the last run, if any */
    uint32_t boot_faults;        /* BOOT_FAULT_* bits */
    int can_status;              /* bxcan_init's answer */
    uint32_t control_calls;
    fw_state state;              /* the controller's, as of the last control tick (for a debugger) */
    fw_fault fault;
    uint32_t fed_progress;       /* the thread's progress when the watchdog was last fed */
    volatile bool feed;          /* the control tick feeds the watchdog (a debugger clears it) */
} board_state;

enum {
    BOOT_FAULT_CLOCK = 1u << 0,
    BOOT_FAULT_CAN = 1u << 1,
    BOOT_FAULT_WATCHDOG = 1u << 2,
    BOOT_FAULT_PREVIOUS = 1u << 3, /* a HardFault or an unexpected interrupt ended the last run */
    BOOT_FAULT_IWDG = 1u << 4,
    BOOT_FAULT_STORAGE = 1u << 5,
};

board_state tse_board;

void CAN1_RX0_IRQHandler(void);
void CAN1_TX_IRQHandler(void);
void CAN1_SCE_IRQHandler(void);

void CAN1_RX0_IRQHandler(void)
{
    bxcan_rx0_isr(&tse_board.can);
}

void CAN1_TX_IRQHandler(void)
{
    bxcan_tx_isr(&tse_board.can);
}

void CAN1_SCE_IRQHandler(void)
{
    bxcan_sce_isr(&tse_board.can);
}

static void on_estop(void *arg)
{
    fw_estop_isr(arg);
}

void board_step(void)
{
    fw_step_tick(tse_board.fw);
}

void board_control(void)
{
    board_state *b = &tse_board;
    fw_control_tick(b->fw);
    ++b->control_calls;
    /* On the internal oscillator every timing is off (and the step interrupt runs slowed): the
     * hardware fault comes back at once if cleared, until a restart finds the crystal. */
    fw_state s = fw_state_of(b->fw);
    if ((b->boot_faults & BOOT_FAULT_CLOCK) && s != FW_STATE_FAULT && s != FW_STATE_ESTOP) {
        fw_report_fault(b->fw, FW_FAULT_HARDWARE);
        s = fw_state_of(b->fw);
    }
    b->state = s;
    b->fault = fw_fault_of(b->fw);
    /* The status LED: steady while enabled, a 1 Hz blink otherwise, fast in a fault. */
    const uint32_t period = s == FW_STATE_FAULT || s == FW_STATE_ESTOP ? 200u : 1000u;
    const bool on = fw_drives_of(b->fw) || (b->control_calls % period) < period / 2u;
    board_led_set(on);
    const uint32_t progress = fw_thread_progress(b->fw);
    if (b->feed && progress != b->fed_progress) {
        b->fed_progress = progress;
        board_iwdg_feed();
    }
}

/* enable_level (fw_enable_level) as board_stepper_hal takes it: 1 high, 0 low, -1 the board's. */
static int enable_level_of(int32_t level)
{
    return level == FW_ENABLE_LEVEL_HIGH ? 1 : level == FW_ENABLE_LEVEL_LOW ? 0 : -1;
}

/* The thread waits for the control tick to take what it handed over: the tick's interrupt wakes
 * it within a control period. */
static void await_tick(void *ctx)
{
    (void)ctx;
    __asm__ volatile("wfi" ::: "memory");
}

/* One line on the board's boot-line USART saying what the start-up found (bootline.h). */
static void boot_line(const board_state *b)
{
    board_bootline_open(b->clocks.apb1_hz, b->clocks.apb2_hz);
    board_bootline_puts("tse-fw node ");
    board_bootline_dec(fw_config_of(b->fw)->node);
    board_bootline_puts(": boot faults ");
    board_bootline_hex(b->boot_faults);
    if ((b->boot_faults & BOOT_FAULT_CLOCK) && b->clocks.crystal.verdict > HSE_CHECK_OK) {
        board_bootline_puts("; ");
        hse_check_say(&b->clocks.crystal, board_bootline_puts);
    } else if (b->boot_faults & BOOT_FAULT_CLOCK) {
        board_bootline_puts("; clock: no ");
        board_bootline_puts(b->clocks.failed);
    }
    if (b->boot_faults & BOOT_FAULT_CAN) {
        board_bootline_puts("; CAN: ");
        board_bootline_puts(bxcan_status_str((bxcan_status)b->can_status));
    }
    if (b->boot_faults & BOOT_FAULT_WATCHDOG)
        board_bootline_puts("; reset by the watchdog");
    if (b->boot_faults & BOOT_FAULT_PREVIOUS)
        board_bootline_puts("; the last run ended in a fault");
    if (b->boot_faults & BOOT_FAULT_IWDG)
        board_bootline_puts("; watchdog not started");
    if (b->boot_faults & BOOT_FAULT_STORAGE)
        board_bootline_puts("; parameter storage");
    board_bootline_puts("\r\n");
}

/* BOOT_ENTER was taken with the drives off (fw_boot_requested): its ACK onto the bus, then a
 * reset with the request that the bootloader stay, as this node at this bit rate (boot_f4.h). */
__attribute__((noreturn)) static void restart_into_bootloader(board_state *b)
{
    for (uint32_t i = 0; i < 1000000u && can_ring_count(&b->can.tx) != 0; ++i)
        board_iwdg_feed();
    for (volatile uint32_t i = 0; i < 200000u; ++i) { /* the last frame leaves its mailbox */
    }
    boot_request_set(BOOT_F4_REQUEST, fw_config_of(b->fw)->node, (uint32_t)fw_params_of(b->fw)->v[FP_CAN_KBPS]);
    __asm__ volatile("dsb" ::: "memory");
    TSE_SCB->AIRCR = SCB_AIRCR_VECTKEY | SCB_AIRCR_SYSRESETREQ;
    for (;;)
        __asm__ volatile("nop");
}

int main(void)
{
    board_state *b = &tse_board;
    if (board_fault_take(&b->previous))
        b->boot_faults |= BOOT_FAULT_PREVIOUS;
    if (board_reset_was_watchdog()) {
        b->boot_faults |= BOOT_FAULT_WATCHDOG;
        board_fault_note(BOARD_FAULT_WATCHDOG_RESET, "IWDG");
    }
    b->clocks = board_clock_init();
    if (b->clocks.failed) {
        b->boot_faults |= BOOT_FAULT_CLOCK;
        board_fault_note(b->clocks.crystal.verdict > HSE_CHECK_OK ? BOARD_FAULT_CRYSTAL : BOARD_FAULT_TIMEOUT,
                         b->clocks.failed);
    }
    board_clock_enable_peripherals();

    fw_hal hal;
    memset(&hal, 0, sizeof hal);
    if (param_log_init(&b->store, flash_f4_ops(flash_f4_feed_iwdg)) != 0)
        b->boot_faults |= BOOT_FAULT_STORAGE;
    hal.storage = param_log_hal(&b->store);
    /* The ENABLE level is the stored enable_level's, known before the pins drive: an active-low
     * driver is never enabled by a pin set low at start-up.  Taken here only (docs/board.md). */
    static fw_param_set stored; /* off the stack, as fw_init's own */
    fw_params_stored(&hal.storage, &stored);
    hal.stepper = board_stepper_hal(b->clocks.apb1_timer_hz, enable_level_of(stored.v[FP_ENABLE_LEVEL]));
    board_pins_init();
    hal.inputs = board_inputs_hal();
    hal.clock = board_clock_hal(b->clocks.apb1_timer_hz);
    hal.can = bxcan_hal(&b->can);

    /* Node 0: the controller's node parameter, as stored (fw_config_of then says which). */
    const fw_config cfg = {0, CONTROL_HZ, STEP_HZ, await_tick, NULL, TSE_BOARD_NAME};
    b->fw = fw_init(&b->fw_mem, &hal, &cfg);
    if (!b->fw)
        board_unexpected_irq(); /* a configuration that cannot run: record and stop */

    /* CAN at the stored bit rate and node id (a change takes effect here, after a save and a
     * restart).  A controller that has not yet seen an idle bus joins it by itself later: not a
     * fault. */
    b->can_status = bxcan_init(&b->can, TSE_CAN1, b->clocks.apb1_hz,
                               (uint32_t)fw_params_of(b->fw)->v[FP_CAN_KBPS] * 1000u, fw_config_of(b->fw)->node, 0);
    if (b->can_status == BXCAN_OK || b->can_status == BXCAN_ERR_LEAVE_INIT) {
        tse_nvic_enable(IRQ_CAN1_RX0, PRIO_CAN);
        tse_nvic_enable(IRQ_CAN1_TX, PRIO_CAN);
        tse_nvic_enable(IRQ_CAN1_SCE, PRIO_CAN);
    } else {
        b->boot_faults |= BOOT_FAULT_CAN;
        board_fault_note(BOARD_FAULT_TIMEOUT, bxcan_status_str((bxcan_status)b->can_status));
    }

    if (board_iwdg_start(WATCHDOG_MS) != 0)
        b->boot_faults |= BOOT_FAULT_IWDG;
    /* The controller refuses to move until a hardware fault is cleared: a clock on the internal
     * oscillator or a CAN controller that never synchronised changes every timing it relies on. */
    if (b->boot_faults)
        fw_report_fault(b->fw, FW_FAULT_HARDWARE);
    b->state = fw_state_of(b->fw);
    b->fault = fw_fault_of(b->fw);
    board_estop_irq_init(on_estop, b->fw);
    boot_line(b);

    b->feed = true;
    b->ticker.timer_hz = b->clocks.apb1_timer_hz;
    /* At 16 MHz a 200 kHz step interrupt would leave the main loop nothing: a tenth of it keeps
     * the board alive and inspectable while it cannot move anyway. */
    if (board_ticker_start(&b->ticker, CONTROL_HZ, b->clocks.failed ? STEP_HZ / 10u : STEP_HZ) != 0)
        board_unexpected_irq();
    /* The controller's thread: what came and what is due, then sleep until an interrupt. */
    for (;;) {
        fw_poll(b->fw);
        if (fw_boot_requested(b->fw))
            restart_into_bootloader(b);
        __asm__ volatile("wfi" ::: "memory");
    }
}
