/* How long a classic CAN data frame with an 11-bit identifier holds the bus, in bit times: start of
 * frame, identifier, RTR, IDE, r0, DLC, the data, the CRC-15 (ISO 11898-1, polynomial 0x4599) and
 * the stuff bits the transmitter inserts after five equal bits in all of those, then the CRC
 * delimiter, ACK slot and delimiter, end of frame (7) and the intermission (3) before the next
 * frame.  8 data bytes take 111 bits without a stuff bit, 135 at the most. */
#ifndef TSECTL_CAN_BITS_H
#define TSECTL_CAN_BITS_H

#include <stdint.h>

unsigned can_frame_bits(uint16_t id, const uint8_t *data, uint8_t len);

#endif
