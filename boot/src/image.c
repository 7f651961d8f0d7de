#include "boot/image.h"

#include <string.h>

#include "boot/crc32.h"

const char *boot_image_status_name(boot_image_status s)
{
    static const char *const names[BOOT_IMAGE_STATUS_COUNT] = {
        "ok", "no_header", "unknown_header", "length", "board", "crc", "vectors",
    };
    return (unsigned)s < BOOT_IMAGE_STATUS_COUNT ? names[s] : "?";
}

uint32_t boot_board_id(const char *name)
{
    return crc32_update(0, name, strlen(name));
}

void boot_image_header_read(const uint8_t *img, boot_image_header *h)
{
    memcpy(h, img + BOOT_IMAGE_HEADER_OFFSET, sizeof *h);
}

uint32_t boot_image_crc(const uint8_t *img, uint32_t length, const boot_image_header *hdr)
{
    const uint32_t head = BOOT_IMAGE_HEADER_OFFSET;
    const uint32_t crc_at = BOOT_IMAGE_CRC_OFFSET;
    const uint32_t tail = BOOT_IMAGE_MIN_LENGTH;
    if (length < tail)
        return 0;
    const uint8_t *h = hdr ? (const uint8_t *)hdr : img + head;
    uint32_t crc = crc32_update(0, img, head);
    crc = crc32_update(crc, h, crc_at - head);
    crc = crc32_update(crc, h + (crc_at + 4u - head), tail - (crc_at + 4u));
    return crc32_update(crc, img + tail, length - tail);
}

static uint32_t word_at(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

boot_image_status boot_image_check(const uint8_t *img, uint32_t area, uint32_t app_start, uint32_t board,
                                   boot_image_header *h)
{
    if (area < BOOT_IMAGE_MIN_LENGTH) {
        memset(h, 0xFF, sizeof *h);
        return BOOT_IMAGE_LENGTH;
    }
    boot_image_header_read(img, h);
    if (h->magic != BOOT_IMAGE_MAGIC)
        return BOOT_IMAGE_NO_HEADER;
    if (h->header_version != BOOT_IMAGE_HEADER_VERSION)
        return BOOT_IMAGE_UNKNOWN_HEADER;
    if (h->length < BOOT_IMAGE_MIN_LENGTH || h->length > area || h->length % 4u != 0)
        return BOOT_IMAGE_LENGTH;
    if (h->board != board)
        return BOOT_IMAGE_BOARD;
    if (boot_image_crc(img, h->length, 0) != h->crc)
        return BOOT_IMAGE_CRC;
    /* Word 1 of the vector table, the reset handler: a Thumb address (bit 0 set) within the image,
     * so that a header pasted onto something else still does not start. */
    const uint32_t reset = word_at(img + 4);
    if ((reset & 1u) == 0 || reset - 1u < app_start + BOOT_IMAGE_MIN_LENGTH || reset - 1u >= app_start + h->length)
        return BOOT_IMAGE_VECTORS;
    return BOOT_IMAGE_OK;
}
