/* An application image as the bootloader takes it (docs/protocol.md, Updating the firmware).
 *
 * An image is the application's flash contents from the application area's first byte: its vector
 * table first (the core starts it from there), then, at BOOT_IMAGE_HEADER_OFFSET, a header the
 * build fills in after linking (host_tools/image_tool): what the image is and for which board,
 * its length and its CRC-32.  The bootloader starts an image only when boot_image_check finds it
 * whole; the CRC covers every byte of the declared length but the header's own crc word. */
#ifndef BOOT_IMAGE_H
#define BOOT_IMAGE_H

#include <stdint.h>

#define BOOT_IMAGE_MAGIC 0x49455354u /* the ASCII bytes T, S, E, I in memory order */
#define BOOT_IMAGE_HEADER_VERSION 1u
/* After the vector table: the STM32F405/407's 16 + 82 vectors take 0x188 bytes, and the table's
 * own alignment (VTOR: 512 bytes for up to 128 vectors) leaves room up to 0x200. */
#define BOOT_IMAGE_HEADER_OFFSET 0x200u
#define BOOT_IMAGE_BOARD_NAME_BYTES 16u

/* Little-endian words in flash, in this order; 48 bytes. */
typedef struct {
    uint32_t magic;          /* BOOT_IMAGE_MAGIC; programmed last of all by the bootloader */
    uint32_t header_version; /* BOOT_IMAGE_HEADER_VERSION */
    uint32_t board;          /* boot_board_id of the board the image is built for */
    uint32_t version;        /* the application's: major << 16 | minor << 8 | patch */
    uint32_t length;         /* the image's bytes from its start, header included; a multiple of 4 */
    uint32_t crc;            /* CRC-32 (boot/crc32.h) of bytes [0, length), this word left out */
    char board_name[BOOT_IMAGE_BOARD_NAME_BYTES]; /* the board's name, NUL-padded (for messages) */
    uint32_t reserved[2];    /* 0 */
} boot_image_header;

_Static_assert(sizeof(boot_image_header) == 48, "the header's layout is the wire's");

#define BOOT_IMAGE_CRC_OFFSET (BOOT_IMAGE_HEADER_OFFSET + 20u)
/* The least an image can be: its vector table and its header. */
#define BOOT_IMAGE_MIN_LENGTH (BOOT_IMAGE_HEADER_OFFSET + (uint32_t)sizeof(boot_image_header))

/* What boot_image_check found. */
typedef enum {
    BOOT_IMAGE_OK = 0,
    BOOT_IMAGE_NO_HEADER,   /* no magic: nothing, or an update that never completed */
    BOOT_IMAGE_UNKNOWN_HEADER, /* a header of a version this bootloader does not read */
    BOOT_IMAGE_LENGTH,      /* a length shorter than its header, not whole words, beyond the area */
    BOOT_IMAGE_BOARD,       /* built for another board */
    BOOT_IMAGE_CRC,         /* the bytes differ from what its CRC says: corrupt or truncated */
    BOOT_IMAGE_VECTORS,     /* its reset vector is not a Thumb address inside the image */
    BOOT_IMAGE_STATUS_COUNT
} boot_image_status;

/* A word for each status, for boot lines and messages: "ok", "no_header", ... */
const char *boot_image_status_name(boot_image_status s);

/* The identity of a board: the CRC-32 of its name's bytes (no NUL).  The board descriptions name
 * each board (TSE_BOARD_NAME); the number is what a header and BOOT_ID carry. */
uint32_t boot_board_id(const char *name);

/* Reads the header of the image at img (the application area, `area` bytes long; memory-mapped
 * flash or a file's bytes) into *h, whatever it holds. */
void boot_image_header_read(const uint8_t *img, boot_image_header *h);

/* The image's CRC as its header defines it: over img[0, length) without the crc word.  With hdr
 * not NULL, the header's bytes are read from *hdr instead of img (the bootloader holds the header
 * back until the rest is written). */
uint32_t boot_image_crc(const uint8_t *img, uint32_t length, const boot_image_header *hdr);

/* Whether img (the application area, area bytes at address app_start) holds a whole image for
 * board: magic, header version, a length within the area, the board, the CRC over the length, a
 * reset vector inside it.  *h gets the header (also when the check fails). */
boot_image_status boot_image_check(const uint8_t *img, uint32_t area, uint32_t app_start, uint32_t board,
                                   boot_image_header *h);

#endif
