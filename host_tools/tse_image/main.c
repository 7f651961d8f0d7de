/* tse-image: the build's post-link step for the bootloader (docs/protocol.md, Updating the
 * firmware).  "tse-image stamp IN.bin OUT.bin --board NAME --version X.Y.Z" writes the image header
 * into the 48 bytes the image keeps for it at 0x200 (erased, 0xFF, or an earlier header): magic,
 * header version, the board's identity (boot_board_id of NAME) and name, the version, the length
 * (IN padded with 0xFF to whole words) and the CRC-32 over it without the crc word.
 * "tse-image show FILE [--board NAME]" prints a header and checks the image as a bootloader for NAME
 * would (exit 0 whole, 3 not).  Exit 2: usage or a file that cannot be an image. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "boot/image.h"

#define MAX_IMAGE (1u << 20)

static uint8_t img[MAX_IMAGE];

static int usage(void)
{
    fprintf(stderr, "usage: tse-image stamp IN.bin OUT.bin --board NAME --version X.Y.Z [--app-start ADDR]\n"
                    "       tse-image show FILE [--board NAME] [--app-start ADDR]\n"
                    "ADDR: the application area's first address (default 0x08004000)\n");
    return 2;
}

static long read_file(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        fprintf(stderr, "tse-image: %s: %s\n", path, strerror(errno));
        return -1;
    }
    const size_t n = fread(img, 1, sizeof img, f);
    const int more = fgetc(f) != EOF;
    (void)fclose(f); /* read only: nothing to lose */
    if (more) {
        fprintf(stderr, "tse-image: %s: longer than %u bytes\n", path, MAX_IMAGE);
        return -1;
    }
    return (long)n;
}

/* X.Y.Z, each 0..255, nothing else. */
static int parse_version(const char *s, uint32_t *v)
{
    uint32_t part[3];
    for (int k = 0; k < 3; ++k) {
        if (*s < '0' || *s > '9')
            return -1;
        char *end;
        const unsigned long x = strtoul(s, &end, 10);
        if (x > 255 || *end != (k < 2 ? '.' : '\0'))
            return -1;
        part[k] = (uint32_t)x;
        s = end + 1;
    }
    *v = part[0] << 16 | part[1] << 8 | part[2];
    return 0;
}

static void put32(uint8_t *p, uint32_t v)
{
    for (int k = 0; k < 4; ++k)
        p[k] = (uint8_t)(v >> (8 * k));
}

static int stamp(const char *in, const char *out, const char *board, uint32_t version)
{
    long n = read_file(in);
    if (n < 0)
        return 2;
    if ((uint32_t)n < BOOT_IMAGE_MIN_LENGTH) {
        fprintf(stderr, "tse-image: %s: %ld bytes, shorter than a vector table and header (%u)\n", in, n,
                BOOT_IMAGE_MIN_LENGTH);
        return 2;
    }
    uint8_t *h = img + BOOT_IMAGE_HEADER_OFFSET;
    int erased = 1;
    for (uint32_t i = 0; i < sizeof(boot_image_header); ++i)
        erased &= h[i] == 0xFF;
    boot_image_header old;
    boot_image_header_read(img, &old);
    if (!erased && old.magic != BOOT_IMAGE_MAGIC) {
        fprintf(stderr, "tse-image: %s: the 48 bytes at 0x%X are neither kept free (0xFF) nor a header: an image "
                        "linked without the header's place would lose code there\n", in, BOOT_IMAGE_HEADER_OFFSET);
        return 2;
    }
    if (strlen(board) == 0 || strlen(board) > BOOT_IMAGE_BOARD_NAME_BYTES) {
        fprintf(stderr, "tse-image: a board name of 1..%u characters: '%s'\n", BOOT_IMAGE_BOARD_NAME_BYTES, board);
        return 2;
    }
    while (n % 4 != 0)
        img[n++] = 0xFF;
    memset(h, 0, sizeof(boot_image_header));
    put32(h, BOOT_IMAGE_MAGIC);
    put32(h + 4, BOOT_IMAGE_HEADER_VERSION);
    put32(h + 8, boot_board_id(board));
    put32(h + 12, version);
    put32(h + 16, (uint32_t)n);
    /* A NUL-padded field (zeroed above), not a C string: at most 16 characters, no NUL of its own.
     * NOLINTNEXTLINE(bugprone-not-null-terminated-result) */
    memcpy(h + 24, board, strlen(board));
    put32(h + 20, boot_image_crc(img, (uint32_t)n, NULL));
    FILE *f = fopen(out, "wb");
    if (!f || fwrite(img, 1, (size_t)n, f) != (size_t)n || fclose(f) != 0) {
        fprintf(stderr, "tse-image: %s: %s\n", out, strerror(errno));
        return 1;
    }
    printf("tse-image: %s: %ld bytes for board %s (0x%08x), version %u.%u.%u, crc 0x%08x\n", out, n, board,
           boot_board_id(board), version >> 16, (version >> 8) & 0xFFu, version & 0xFFu,
           boot_image_crc(img, (uint32_t)n, NULL));
    return 0;
}

static int show(const char *path, const char *board, uint32_t app_start)
{
    const long n = read_file(path);
    if (n < 0)
        return 2;
    if ((uint32_t)n < BOOT_IMAGE_MIN_LENGTH) {
        fprintf(stderr, "tse-image: %s: %ld bytes, shorter than a header\n", path, n);
        return 2;
    }
    boot_image_header h;
    boot_image_header_read(img, &h);
    char name[BOOT_IMAGE_BOARD_NAME_BYTES + 1] = {0};
    memcpy(name, h.board_name, BOOT_IMAGE_BOARD_NAME_BYTES);
    printf("magic 0x%08x, header %u, board %s (0x%08x), version %u.%u.%u, length %u (file %ld), crc 0x%08x\n",
           h.magic, h.header_version, name, h.board, h.version >> 16, (h.version >> 8) & 0xFFu, h.version & 0xFFu,
           h.length, n, h.crc);
    const boot_image_status s =
        boot_image_check(img, (uint32_t)n, app_start, board ? boot_board_id(board) : h.board, &h);
    printf("check%s%s: %s\n", board ? " for board " : "", board ? board : "", boot_image_status_name(s));
    return s == BOOT_IMAGE_OK ? 0 : 3;
}

int main(int argc, char **argv)
{
    if (argc < 3)
        return usage();
    const char *board = NULL, *version = NULL;
    uint32_t app_start = 0x08004000u;
    const char *files[2] = {0, 0};
    int nfiles = 0;
    for (int i = 2; i < argc; ++i) {
        if (!strcmp(argv[i], "--board") && i + 1 < argc)
            board = argv[++i];
        else if (!strcmp(argv[i], "--version") && i + 1 < argc)
            version = argv[++i];
        else if (!strcmp(argv[i], "--app-start") && i + 1 < argc)
            app_start = (uint32_t)strtoul(argv[++i], NULL, 0);
        else if (argv[i][0] != '-' && nfiles < 2)
            files[nfiles++] = argv[i];
        else
            return usage();
    }
    if (!strcmp(argv[1], "stamp")) {
        uint32_t v;
        if (nfiles != 2 || !board || !version || parse_version(version, &v) != 0)
            return usage();
        return stamp(files[0], files[1], board, v);
    }
    if (!strcmp(argv[1], "show") && nfiles == 1)
        return show(files[0], board, app_start);
    return usage();
}
