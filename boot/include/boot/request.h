/* The application's request that the bootloader stay (BOOT_ENTER), carried across a reset in RAM
 * that neither start-up code clears (a no-init section at one address, the same in both images).
 *
 * A reset keeps SRAM; a power cut does not, and what SRAM holds after one is noise.  So the
 * request is a magic word and its complement around the node: noise passes for a request with a
 * chance of 2^-64 at most, and a power cut (the update's worst case) starts the application if it
 * is whole, or the bootloader if not. */
#ifndef BOOT_REQUEST_H
#define BOOT_REQUEST_H

#include <stdbool.h>
#include <stdint.h>

#define BOOT_REQUEST_MAGIC 0x52514254u /* the ASCII bytes T, B, Q, R in memory order */

typedef struct {
    uint32_t magic;
    uint32_t node;  /* the node the application ran as: the bootloader answers as it */
    uint32_t kbps;  /* and the bit rate it ran at (its can_kbps) */
    uint32_t check; /* ~magic ^ node ^ kbps */
} boot_request;

/* Asks the next start to stay in the bootloader, as node at kbps. */
void boot_request_set(volatile boot_request *r, uint8_t node, uint32_t kbps);

/* Whether a request is there (node 1..15, kbps 1..1000); takes it (clears it) either way, so that
 * it is answered once.  *node and *kbps get its own (untouched without one). */
bool boot_request_take(volatile boot_request *r, uint8_t *node, uint32_t *kbps);

#endif
