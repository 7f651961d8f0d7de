#include "boot/request.h"

void boot_request_set(volatile boot_request *r, uint8_t node)
{
    r->node = node;
    r->check = ~BOOT_REQUEST_MAGIC ^ node;
    r->magic = BOOT_REQUEST_MAGIC;
}

bool boot_request_take(volatile boot_request *r, uint8_t *node)
{
    const bool there = r->magic == BOOT_REQUEST_MAGIC && r->check == (~BOOT_REQUEST_MAGIC ^ r->node) &&
                       r->node >= 1u && r->node <= 15u;
    if (there)
        *node = (uint8_t)r->node;
    r->magic = 0;
    r->check = 0;
    r->node = 0;
    return there;
}
