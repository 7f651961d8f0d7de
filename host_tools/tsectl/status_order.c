#include "status_order.h"

bool status_order_note(status_order *o, uint16_t counter)
{
    if (o->seen) {
        const uint16_t d = (uint16_t)(counter - o->last);
        if (d == 0 || d >= 0x8000u) {
            ++o->disorder;
            o->in_order = 0;
        } else if (++o->in_order >= 20u) {
            o->disorder = 0;
        }
    }
    o->seen = true;
    o->last = counter;
    return o->disorder >= 3u;
}
