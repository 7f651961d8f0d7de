/* The fault handlers and the fault record (hal_stm32f4/fault.h). */
#include "hal_stm32f4/fault.h"

#include "hal_stm32f4/regs_core.h"

__attribute__((section(".noinit"))) volatile board_fault_record tse_fault_record;


static uint32_t ipsr(void)
{
    uint32_t v;
    __asm__ volatile("mrs %0, ipsr" : "=r"(v));
    return v;
}

static void begin_record(board_fault_kind kind)
{
    const uint32_t count = tse_fault_record.magic == BOARD_FAULT_MAGIC ? tse_fault_record.count : 0u;
    tse_fault_record.kind = kind;
    tse_fault_record.count = count + 1u;
    tse_fault_record.exc = ipsr() & 0x1FFu;
    tse_fault_record.where = 0;
}

/* Stops the machine first, then writes down what happened, then waits for the watchdog (or a
 * debugger) with interrupts off: nothing after a fault is trusted to step a motor. */
__attribute__((noreturn)) static void stop_here(void)
{
    tse_fault_record.magic = BOARD_FAULT_MAGIC;
    for (;;)
        __asm__ volatile("cpsid i\n\twfi" ::: "memory");
}

__attribute__((noreturn)) void board_hardfault_record(const uint32_t *frame)
{
    board_outputs_safe();
    begin_record(BOARD_FAULT_HARDFAULT);
    tse_fault_record.cfsr = TSE_SCB->CFSR;
    tse_fault_record.hfsr = TSE_SCB->HFSR;
    tse_fault_record.mmfar = TSE_SCB->MMFAR;
    tse_fault_record.bfar = TSE_SCB->BFAR;
    /* The exception frame: r0, r1, r2, r3, r12, lr, pc, xpsr. */
    tse_fault_record.lr = frame[5];
    tse_fault_record.pc = frame[6];
    tse_fault_record.psr = frame[7];
    stop_here();
}

__attribute__((noreturn)) void board_unexpected_irq(void)
{
    board_outputs_safe();
    begin_record(BOARD_FAULT_UNEXPECTED_IRQ);
    stop_here();
}

void board_fault_note(board_fault_kind kind, const char *where)
{
    begin_record(kind);
    tse_fault_record.where = where;
    tse_fault_record.magic = BOARD_FAULT_MAGIC;
}

int board_fault_take(board_fault_record *out)
{
    if (tse_fault_record.magic != BOARD_FAULT_MAGIC)
        return 0;
    out->magic = tse_fault_record.magic;
    out->kind = tse_fault_record.kind;
    out->count = tse_fault_record.count;
    out->exc = tse_fault_record.exc;
    out->cfsr = tse_fault_record.cfsr;
    out->hfsr = tse_fault_record.hfsr;
    out->mmfar = tse_fault_record.mmfar;
    out->bfar = tse_fault_record.bfar;
    out->pc = tse_fault_record.pc;
    out->lr = tse_fault_record.lr;
    out->psr = tse_fault_record.psr;
    out->where = tse_fault_record.where;
    tse_fault_record.magic = 0;
    return 1;
}
