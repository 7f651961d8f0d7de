/* The emulated board's CAN channel (docs/emulator.md): a byte stream of 16-byte records, one per
 * frame, both ways, little-endian: u32 can_id in SocketCAN's layout (bit 31 extended, 30 RTR,
 * 29 error frame), u8 len (0..8), u8 flags (0), u16 reserved (0), u8 data[8] (bytes past len 0). */
#ifndef EMU_LINK_CAN_RECORD_H
#define EMU_LINK_CAN_RECORD_H

#include <stdint.h>

#define CAN_RECORD_SIZE 16

typedef struct {
    uint32_t can_id;
    uint8_t len;
    uint8_t data[8];
} can_record;

void can_record_pack(const can_record *r, uint8_t out[CAN_RECORD_SIZE]);

/* Returns 0, or -1 naming in *why what makes the record one the channel does not carry (a length
 * above 8, flags or reserved bytes set, an error frame, an identifier beyond its format). */
int can_record_unpack(const uint8_t in[CAN_RECORD_SIZE], can_record *r, const char **why);

#endif
