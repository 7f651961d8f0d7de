/* The bootloader's first decision after a reset: start the application, or stay on the bus for
 * an update.  It starts the application only when the application area holds a whole image for
 * this board (boot_image_check: header, length, board, CRC over the declared length, reset vector)
 * and no update was asked for (boot/request.h); in every other case it stays, so that a cut or
 * refused update, or a foreign image, leaves a board that takes the update again. */
#ifndef BOOT_DECIDE_H
#define BOOT_DECIDE_H

#include <stdbool.h>
#include <stdint.h>

#include "boot/image.h"
#include "boot/layout.h"

typedef enum {
    BOOT_START_APP,     /* a whole image and no request */
    BOOT_STAY_REQUEST,  /* the application asked (BOOT_ENTER) */
    BOOT_STAY_NO_IMAGE  /* no whole image for this board: *why says what was wrong */
} boot_choice;

/* flash: the region from l->flash_base, memory-mapped.  *why gets the image's status (checked
 * also when a request makes the choice, for BOOT_APP). */
boot_choice boot_decide(const boot_layout *l, const uint8_t *flash, uint32_t board, bool requested,
                        boot_image_status *why, boot_image_header *h);

#endif
