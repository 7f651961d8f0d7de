#include "can_record.h"

#include <string.h>

#define EFF_FLAG 0x80000000u
#define RTR_FLAG 0x40000000u
#define ERR_FLAG 0x20000000u

void can_record_pack(const can_record *r, uint8_t out[CAN_RECORD_SIZE])
{
    memset(out, 0, CAN_RECORD_SIZE);
    for (int i = 0; i < 4; ++i)
        out[i] = (uint8_t)(r->can_id >> (8 * i));
    const uint8_t len = r->len > 8 ? 8 : r->len;
    out[4] = len;
    memcpy(out + 8, r->data, len);
}

int can_record_unpack(const uint8_t in[CAN_RECORD_SIZE], can_record *r, const char **why)
{
    r->can_id = (uint32_t)in[0] | (uint32_t)in[1] << 8 | (uint32_t)in[2] << 16 | (uint32_t)in[3] << 24;
    r->len = in[4];
    memset(r->data, 0, sizeof r->data);
    if (r->len > 8)
        return *why = "a length above 8", -1;
    if (in[5] || in[6] || in[7])
        return *why = "flags or reserved bytes set", -1;
    if (r->can_id & ERR_FLAG)
        return *why = "an error frame", -1;
    const uint32_t id = r->can_id & ~(EFF_FLAG | RTR_FLAG);
    if (id > ((r->can_id & EFF_FLAG) ? 0x1FFFFFFFu : 0x7FFu))
        return *why = "an identifier beyond its format", -1;
    memcpy(r->data, in + 8, r->len);
    return 0;
}
