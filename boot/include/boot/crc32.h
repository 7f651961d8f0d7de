/* CRC-32 as Ethernet, zlib and PNG compute it (IEEE 802.3: polynomial 0x04C11DB7 reflected,
 * initial value and final XOR 0xFFFFFFFF; the check value of "123456789" is 0xCBF43926), so that
 * a host checks an image with any library's crc32.
 *
 * Incremental: crc32_update(crc32_update(0, a, n), b, m) is the CRC of a then b.  Small rather than
 * fast (a 16-entry table, two steps a byte): the bootloader's budget is 16 KiB. */
#ifndef BOOT_CRC32_H
#define BOOT_CRC32_H

#include <stddef.h>
#include <stdint.h>

/* The CRC of the bytes seen so far (crc, 0 for none) followed by p[0..n). */
uint32_t crc32_update(uint32_t crc, const void *p, size_t n);

#endif
