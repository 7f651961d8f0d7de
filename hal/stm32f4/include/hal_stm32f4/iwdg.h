/* The independent watchdog: once started it cannot be stopped, and resets the core unless fed
 * within the timeout.  The board feeds it from the main loop after each control call, so it
 * proves that the control tick fires and the main loop runs. */
#ifndef TSE_BOARD_IWDG_H
#define TSE_BOARD_IWDG_H

#include <stdint.h>

/* Starts it with a timeout of about timeout_ms (LSI 32 kHz nominal, 17..47 kHz over parts and
 * temperature: the real timeout is 0.7 to 1.9 times this).  Returns 0, or -1 when the register
 * update flags never cleared (the watchdog then runs with its reset values: 512 ms). */
int board_iwdg_start(uint32_t timeout_ms);
void board_iwdg_feed(void);

/* True when the last reset came from the watchdog (and clears the reset flags). */
int board_reset_was_watchdog(void);

#endif
