#include "can_bits.h"

unsigned can_frame_bits(uint16_t id, const uint8_t *data, uint8_t len)
{
    /* The bits from the start of frame to the CRC's last, MSB first within each field. */
    uint8_t bits[1 + 11 + 3 + 4 + 64 + 15];
    unsigned n = 0;
    bits[n++] = 0;
    for (int k = 10; k >= 0; --k)
        bits[n++] = (id >> k) & 1u;
    bits[n++] = 0; /* RTR: data frame */
    bits[n++] = 0; /* IDE: 11-bit identifier */
    bits[n++] = 0; /* r0 */
    for (int k = 3; k >= 0; --k)
        bits[n++] = (len >> k) & 1u;
    for (unsigned b = 0; b < len; ++b)
        for (int k = 7; k >= 0; --k)
            bits[n++] = (data[b] >> k) & 1u;
    unsigned crc = 0;
    for (unsigned i = 0; i < n; ++i) {
        const unsigned next = bits[i] ^ ((crc >> 14) & 1u);
        crc = (crc << 1) & 0x7FFFu;
        if (next)
            crc ^= 0x4599u;
    }
    for (int k = 14; k >= 0; --k)
        bits[n++] = (crc >> k) & 1u;
    /* Stuffing: after five equal bits the complement goes in, and counts in the next run. */
    unsigned stuffed = 0, run = 0;
    uint8_t last = 2;
    for (unsigned i = 0; i < n; ++i) {
        run = bits[i] == last ? run + 1 : 1;
        last = bits[i];
        if (run == 5) {
            ++stuffed;
            last = !last;
            run = 1;
        }
    }
    return n + stuffed + 1 + 2 + 7 + 3;
}
