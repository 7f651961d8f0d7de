/* The boot line: one line of text when the image starts, on USART1 TX (PA9, 115200 8N1,
 * pinmap.h), saying what the start-up found.  For a 3.3 V serial adapter on the bench, and for
 * an emulator's console (QEMU's netduinoplus2 and tse-f407 model USART1: -serial).  Not
 * semihosting, which stops a board that has no debugger attached.
 *
 * Blocking and bounded: each character waits for the transmitter at most BOOTLINE_WAIT_POLLS
 * polls, so a dead USART costs a few milliseconds, never a hang.  A line of 80 characters takes
 * 7 ms at 115200 bit/s. */
#ifndef TSE_BOARD_BOOTLINE_H
#define TSE_BOARD_BOOTLINE_H

#include <stdint.h>

#define BOOTLINE_BAUD 115200u
#define BOOTLINE_WAIT_POLLS 20000u

/* Clocks USART1, puts PA9 on it, and sets 115200 bit/s from pclk2_hz (the APB2 clock). */
void board_bootline_open(uint32_t pclk2_hz);

void board_bootline_puts(const char *s);
void board_bootline_hex(uint32_t v); /* "0x" and at least two hexadecimal digits */
void board_bootline_dec(uint32_t v);

#endif
