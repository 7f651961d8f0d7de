/* The boot line: one line of text when the image starts, on the board description's USART TX
 * (board_desc.h; USART1 on PA9 on gen_f405; 115200 8N1), saying what the start-up found.  For a 3.3 V serial adapter on the bench, and for
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

/* Clocks the description's USART (1, 2, 3 or 6), puts its TX pin on it, and sets 115200 bit/s
 * from its bus clock: pclk1_hz (APB1: USART2, USART3) or pclk2_hz (APB2: USART1, USART6). */
void board_bootline_open(uint32_t pclk1_hz, uint32_t pclk2_hz);

void board_bootline_puts(const char *s);
void board_bootline_hex(uint32_t v); /* "0x" and at least two hexadecimal digits */
void board_bootline_dec(uint32_t v);

#endif
