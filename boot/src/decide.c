#include "boot/decide.h"

boot_choice boot_decide(const boot_layout *l, const uint8_t *flash, uint32_t board, bool requested,
                        boot_image_status *why, boot_image_header *h)
{
    *why = boot_image_check(flash + l->app_offset, l->app_bytes, l->flash_base + l->app_offset, board, h);
    if (requested)
        return BOOT_STAY_REQUEST;
    return *why == BOOT_IMAGE_OK ? BOOT_START_APP : BOOT_STAY_NO_IMAGE;
}
