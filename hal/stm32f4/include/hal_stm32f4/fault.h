/* What the board records when it stops abnormally, kept across a reset in .noinit RAM: the
 * HardFault (and the other fault exceptions), an interrupt nobody handles, a hardware wait that
 * timed out at start-up, a reset by the independent watchdog.  After the reset the application
 * reports it (FW_FAULT_HARDWARE) and a debugger can read `tse_fault_record`. */
#ifndef TSE_BOARD_FAULT_H
#define TSE_BOARD_FAULT_H

#include <stdint.h>

typedef enum {
    BOARD_FAULT_NONE = 0,
    BOARD_FAULT_HARDFAULT = 1,   /* a fault exception: registers below */
    BOARD_FAULT_UNEXPECTED_IRQ,  /* an enabled interrupt without a handler: irq below */
    BOARD_FAULT_WATCHDOG_RESET,  /* the IWDG reset the core: the main loop stopped */
    BOARD_FAULT_TIMEOUT,         /* a hardware flag never came: `where` names it */
    BOARD_FAULT_CRYSTAL,         /* the crystal measured off its frequency (hse_check.h) */
} board_fault_kind;

typedef struct {
    uint32_t magic;   /* BOARD_FAULT_MAGIC when the record is valid */
    uint32_t kind;    /* board_fault_kind */
    uint32_t count;   /* faults recorded since power-up */
    uint32_t exc;     /* active exception number (IPSR) */
    uint32_t cfsr, hfsr, mmfar, bfar;
    uint32_t pc, lr, psr;
    const char *where; /* for BOARD_FAULT_TIMEOUT: the wait that timed out (a string in flash) */
} board_fault_record;

#define BOARD_FAULT_MAGIC 0x46415554u /* "TUAF" */

extern volatile board_fault_record tse_fault_record;

/* Records a fault that is not an exception (a timeout, a watchdog reset seen at boot). */
void board_fault_note(board_fault_kind kind, const char *where);

/* True when the record holds a fault from before the last reset (and clears its magic so that
 * it is reported once). */
int board_fault_take(board_fault_record *out);

/* Entered from the exception handlers of startup.c: record, stop the outputs, wait for the
 * watchdog.  frame: the exception's stacked r0..xpsr. */
__attribute__((noreturn)) void board_hardfault_record(const uint32_t *frame);
__attribute__((noreturn)) void board_unexpected_irq(void);

/* Stops every output that moves the machine, without any help from the firmware: called from
 * the fault handlers.  Provided by the step output driver. */
void board_outputs_safe(void);

#endif
