#include "boot/request.h"

void boot_request_set(volatile boot_request *r, uint8_t node, uint32_t kbps)
{
    r->node = node;
    r->kbps = kbps;
    r->check = ~BOOT_REQUEST_MAGIC ^ node ^ kbps;
    r->magic = BOOT_REQUEST_MAGIC;
}

bool boot_request_take(volatile boot_request *r, uint8_t *node, uint32_t *kbps)
{
    const uint32_t n = r->node, k = r->kbps;
    const bool there = r->magic == BOOT_REQUEST_MAGIC && r->check == (~BOOT_REQUEST_MAGIC ^ n ^ k) && n >= 1u &&
                       n <= 15u && k >= 1u && k <= 1000u;
    if (there) {
        *node = (uint8_t)n;
        *kbps = k;
    }
    r->magic = 0;
    r->check = 0;
    r->node = 0;
    r->kbps = 0;
    return there;
}
