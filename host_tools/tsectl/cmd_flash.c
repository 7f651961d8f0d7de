#define _POSIX_C_SOURCE 200809L
/* tsectl flash IMAGE: a firmware update over the bus (docs/protocol.md, Updating the firmware).
 *
 * The image is checked first, with nothing sent (its header, its length, its own CRC); then the
 * node is asked what it is (BOOT_QUERY; an application refuses it `state` and is sent BOOT_ENTER,
 * which it refuses while its drives may be on), and an image for another board, or longer than
 * the application area, is refused before anything is erased.  Then ERASE (timed apart), the
 * blocks with BOOT_WINDOW_BLOCKS in flight (a block refused for its frames or CRC, or out of order
 * behind one, is sent again, 5 times at most), VERIFY, BOOT_QUERY again to see the image there
 * with its version and CRC, and BOOT_START (unless --no-start).  It prints the transfer's duration and rate against
 * the bus's limit, 8 x length / bit rate, at --bitrate (default 500000): the rate reached on the
 * wall clock, and the time the frames sent and answered need on a bus of that rate, stuff bits
 * counted (on vcan, which has no bit rate, the wall clock is no measure of a real bus). */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "boot/crc32.h"
#include "boot/image.h"
#include "boot/update.h"
#include "can_bits.h"
#include "commands.h"
#include "progress.h"

#define MAX_IMAGE (1u << 20)
#define RETRIES 5

static uint8_t image[MAX_IMAGE + 8];
static uint32_t image_len;
static boot_image_header header;
static long bitrate = 500000;
static int no_start; /* --no-start: leave the board in its bootloader */
static double bus_bits; /* bit times of the update's frames, both ways */

static double now_s(void)
{
    return (double)link_now_us() / 1e6;
}

int check_flash(int argc, char **argv, int *done)
{
    (void)done;
    const char *path = NULL;
    for (int i = 0; i < argc; ++i) {
        if (!strcmp(argv[i], "--bitrate") && i + 1 < argc) {
            char *end;
            bitrate = strtol(argv[++i], &end, 10);
            if (*end || bitrate < 10000 || bitrate > 1000000)
                return usage_error(NULL, "--bitrate takes 10000..1000000 bit/s", argv[i]);
        } else if (!strcmp(argv[i], "--no-start")) {
            no_start = 1;
        } else if (argv[i][0] != '-' && !path)
            path = argv[i];
        else
            return usage_error(NULL, "unexpected argument", argv[i]);
    }
    if (!path)
        return usage_error(NULL, "an image file is needed", NULL);
    FILE *f = fopen(path, "rb");
    if (!f) {
        ctl_error("%s: %s", path, strerror(errno));
        return EXIT_USAGE;
    }
    const size_t n = fread(image, 1, MAX_IMAGE + 1u, f);
    (void)fclose(f); /* read only: nothing to lose */
    if (n > MAX_IMAGE || n < BOOT_IMAGE_MIN_LENGTH) {
        ctl_error("%s: %zu bytes: not an image (%u to %u bytes)", path, n, BOOT_IMAGE_MIN_LENGTH, MAX_IMAGE);
        return EXIT_USAGE;
    }
    image_len = (uint32_t)n;
    boot_image_header_read(image, &header);
    if (header.magic != BOOT_IMAGE_MAGIC || header.header_version != BOOT_IMAGE_HEADER_VERSION) {
        ctl_error("%s: no image header at 0x%X (tse-image stamp writes it after linking)", path,
                  BOOT_IMAGE_HEADER_OFFSET);
        return EXIT_USAGE;
    }
    if (header.length != image_len) {
        ctl_error("%s: its header says %u bytes, the file has %u", path, header.length, image_len);
        return EXIT_USAGE;
    }
    if (boot_image_crc(image, image_len, NULL) != header.crc) {
        ctl_error("%s: its CRC-32 is 0x%08x, its header says 0x%08x: a damaged image", path,
                  boot_image_crc(image, image_len, NULL), header.crc);
        return EXIT_USAGE;
    }
    memset(image + image_len, 0xFF, 8); /* the last frame's padding */
    return EXIT_OK;
}

static void count_bits(proto_msg m, const int32_t *v, uint8_t node)
{
    hal_can_frame f;
    if (proto_encode_values(m, node, v, &f) == 0)
        bus_bits += can_frame_bits(f.id, f.data, f.len);
}

/* link_send (which waits while the interface's queue is full), the frame counted on the bus. */
static int send_wait(tlink *l, proto_msg m, const int32_t *v)
{
    if (link_send(l, m, v) != 0)
        return -1;
    count_bits(m, v, l->node);
    return 0;
}

typedef struct {
    uint32_t board, app_start, app_size, block_bytes, app_crc;
    int major, minor, valid, app_major, app_minor, app_patch;
} boot_info;

/* BOOT_QUERY and its three answers.  Returns EXIT_OK, EXIT_REJECTED with *rej, or a failure. */
static int query(tlink *l, uint8_t seq, boot_info *b, proto_message *rej)
{
    const int32_t v[1] = {seq};
    proto_message m;
    const int rc = ctl_ask(l, PM_BOOT_QUERY, v, PM_BOOT_ID, -1, "BOOT_ID", &m);
    if (rc != EXIT_OK) {
        *rej = m;
        return rc;
    }
    b->major = (int)m.v[0];
    b->minor = (int)m.v[1];
    b->board = (uint32_t)m.v[2] | (uint32_t)m.v[3] << 16;
    b->block_bytes = (uint32_t)m.v[4];
    int got = 0;
    const uint64_t end = link_now_us() + (uint64_t)tsectl_timeout_ms * 1000u;
    while (got != 3 && link_now_us() < end && !tsectl_interrupted) {
        if (link_recv(l, &m, 50) != 1)
            continue;
        if (m.msg == PM_BOOT_LAYOUT) {
            b->app_start = (uint32_t)m.v[0];
            b->app_size = (uint32_t)m.v[1];
            got |= 1;
        } else if (m.msg == PM_BOOT_APP) {
            b->valid = (int)m.v[0];
            b->app_major = (int)m.v[1];
            b->app_minor = (int)m.v[2];
            b->app_patch = (int)m.v[3];
            b->app_crc = (uint32_t)m.v[4] | (uint32_t)m.v[5] << 16;
            got |= 2;
        }
    }
    if (got != 3) {
        ctl_error("node %u acknowledged BOOT_QUERY but did not say its layout and application", l->node);
        return EXIT_TIMEOUT;
    }
    return EXIT_OK;
}

/* Into the bootloader: BOOT_QUERY, and when an application answers it, BOOT_ENTER and BOOT_QUERY
 * until the bootloader answers (the board restarts meanwhile). */
static int reach_bootloader(tlink *l, boot_info *b)
{
    proto_message rej;
    int rc = query(l, 0, b, &rej);
    if (rc == EXIT_OK)
        return EXIT_OK;
    if (rc != EXIT_REJECTED || rej.v[2] != FW_REASON_STATE) {
        if (rc == EXIT_REJECTED)
            ctl_print_reject(&rej);
        return rc;
    }
    printf("node %u runs its application: asking it to restart into its bootloader\n", l->node);
    const int32_t enter[2] = {0, 0x544F4F42};
    if (link_send(l, PM_BOOT_ENTER, enter) != 0)
        return EXIT_BUS;
    proto_message ack;
    rc = ctl_answer(l, proto_table[PM_BOOT_ENTER].function, 0, &ack, &rej);
    if (rc == EXIT_REJECTED) {
        ctl_print_reject(&rej);
        ctl_error("node %u stays in its application (disable the drives first: 'tsectl disable')", l->node);
        return rc;
    }
    if (rc != EXIT_OK)
        return rc;
    const int saved = tsectl_timeout_ms;
    tsectl_timeout_ms = 250;
    rc = EXIT_TIMEOUT;
    for (int i = 0; i < 40 && rc != EXIT_OK && !tsectl_interrupted; ++i)
        rc = query(l, (uint8_t)(i + 1), b, &rej);
    tsectl_timeout_ms = saved;
    if (rc != EXIT_OK)
        ctl_error("node %u's bootloader did not answer within 10 s of BOOT_ENTER", l->node);
    return rc;
}

static int send_block(tlink *l, uint32_t blk, uint8_t seq, uint32_t block_bytes)
{
    const uint32_t off = blk * block_bytes;
    const uint32_t bytes = image_len - off < block_bytes ? image_len - off : block_bytes;
    const uint32_t frames = (bytes + 7u) / 8u;
    const uint32_t crc = crc32_update(0, image + off, bytes);
    const int32_t w[5] = {seq, (int32_t)blk, (int32_t)frames, (int32_t)(crc & 0xFFFFu), (int32_t)(crc >> 16)};
    if (send_wait(l, PM_BOOT_WRITE, w) != 0)
        return -1;
    for (uint32_t k = 0; k < frames; ++k) {
        const uint8_t *p = image + off + 8u * k;
        int32_t d[4];
        for (int j = 0; j < 4; ++j)
            d[j] = p[2 * j] | p[2 * j + 1] << 8;
        if (send_wait(l, PM_BOOT_DATA, d) != 0)
            return -1;
    }
    return 0;
}

/* An answer to a command, counted on the bus; a REJECT printed. */
static int answered(tlink *l, proto_msg m, uint8_t seq, proto_message *ack)
{
    proto_message rej;
    const int rc = ctl_answer(l, proto_table[m].function, seq, ack, &rej);
    if (rc == EXIT_OK)
        count_bits(PM_ACK, ack->v, l->node);
    if (rc == EXIT_REJECTED)
        ctl_print_reject(&rej);
    return rc;
}

static int transfer(tlink *l, uint32_t block_bytes)
{
    const uint32_t blocks = (image_len + block_bytes - 1u) / block_bytes;
    const uint8_t seq0 = 0x40;
    uint32_t next_send = 0, next_ack = 0;
    int retries = 0;
    progress p;
    progress_start(&p, "writing", -1);
    while (next_ack < blocks) {
        while (next_send < blocks && next_send - next_ack < BOOT_WINDOW_BLOCKS) {
            if (send_block(l, next_send, (uint8_t)(seq0 + next_send), block_bytes) != 0) {
                ctl_error("cannot send on the bus");
                return EXIT_BUS;
            }
            ++next_send;
        }
        proto_message a, rej;
        const int rc = ctl_answer(l, proto_table[PM_BOOT_WRITE].function, (uint8_t)(seq0 + next_ack), &a, &rej);
        if (rc == EXIT_OK) {
            count_bits(PM_ACK, a.v, l->node);
            ++next_ack;
            char detail[64];
            snprintf(detail, sizeof detail, "block %u of %u", next_ack, blocks);
            progress_update(&p, (double)next_ack / blocks, detail);
            continue;
        }
        if (rc != EXIT_REJECTED)
            return rc;
        const fw_reason why = (fw_reason)rej.v[2];
        if ((why != FW_REASON_CRC && why != FW_REASON_LENGTH && why != FW_REASON_ORDER) || retries >= RETRIES) {
            ctl_print_reject(&rej);
            ctl_error("block %u of the image refused: the update stops (the board stays in its bootloader; "
                      "'tsectl flash' again starts over)", next_ack);
            return rc;
        }
        ++retries;
        ctl_error("warning: block %u refused (%s), sending again from it", next_ack,
                  proto_enum_name(proto_reason_names, (int)why));
        for (uint32_t b = next_ack + 1u; b < next_send; ++b) /* the one behind it: refused order */
            (void)ctl_answer(l, proto_table[PM_BOOT_WRITE].function, (uint8_t)(seq0 + b), &a, &rej);
        next_send = next_ack;
    }
    return EXIT_OK;
}

int run_flash(tlink *l, int argc, char **argv)
{
    (void)argc, (void)argv;
    char name[BOOT_IMAGE_BOARD_NAME_BYTES + 1] = {0};
    memcpy(name, header.board_name, BOOT_IMAGE_BOARD_NAME_BYTES);
    printf("image: %u bytes, version %u.%u.%u, for board %s (0x%08x), crc 0x%08x\n", image_len, header.version >> 16,
           (header.version >> 8) & 0xFFu, header.version & 0xFFu, name, header.board, header.crc);
    boot_info b;
    int rc = reach_bootloader(l, &b);
    if (rc != EXIT_OK)
        return rc;
    printf("node %u: bootloader %d.%d, board 0x%08x, application area 0x%08x, %u bytes; ", l->node, b.major, b.minor,
           b.board, b.app_start, b.app_size);
    if (b.valid)
        printf("application %d.%d.%d (crc 0x%08x)\n", b.app_major, b.app_minor, b.app_patch, b.app_crc);
    else
        printf("no application\n");
    /* Refused before anything is erased. */
    if (b.board != header.board) {
        ctl_error("the image is for board %s (0x%08x), node %u is board 0x%08x: nothing erased", name, header.board,
                  l->node, b.board);
        return EXIT_REJECTED;
    }
    if (image_len > b.app_size) {
        ctl_error("the image's %u bytes do not fit node %u's application area of %u: nothing erased", image_len,
                  l->node, b.app_size);
        return EXIT_REJECTED;
    }
    boot_image_header h;
    const boot_image_status s = boot_image_check(image, image_len, b.app_start, b.board, &h);
    if (s != BOOT_IMAGE_OK) {
        ctl_error("the image would not start at 0x%08x (%s): nothing erased", b.app_start, boot_image_status_name(s));
        return EXIT_REJECTED;
    }
    if (b.block_bytes % 8u != 0 || b.block_bytes == 0) {
        ctl_error("node %u's block size %u is not a whole number of frames", l->node, b.block_bytes);
        return EXIT_REJECTED;
    }
    /* Erase: seconds on a board (up to 4 s a sector by flash_f4's bound). */
    const int saved = tsectl_timeout_ms;
    tsectl_timeout_ms = saved > 60000 ? saved : 60000;
    const double t_erase = now_s();
    const int32_t er[2] = {1, (int32_t)image_len};
    proto_message a;
    rc = link_send(l, PM_BOOT_ERASE, er) == 0 ? answered(l, PM_BOOT_ERASE, 1, &a) : EXIT_BUS;
    tsectl_timeout_ms = saved;
    if (rc != EXIT_OK)
        return rc;
    printf("erased %d sectors in %.2f s\n", (int)a.v[4], now_s() - t_erase);
    bus_bits = 0;
    const double t0 = now_s();
    rc = transfer(l, b.block_bytes);
    if (rc != EXIT_OK)
        return rc;
    const double wall = now_s() - t0;
    const int32_t ver[1] = {2};
    if ((rc = link_send(l, PM_BOOT_VERIFY, ver) == 0 ? answered(l, PM_BOOT_VERIFY, 2, &a) : EXIT_BUS) != EXIT_OK)
        return rc;
    proto_message rej;
    if ((rc = query(l, 3, &b, &rej)) != EXIT_OK)
        return rc;
    if (!b.valid || b.app_crc != header.crc ||
        (uint32_t)(b.app_major << 16 | b.app_minor << 8 | b.app_patch) != header.version) {
        ctl_error("node %u's bootloader does not report the image written (valid %d, crc 0x%08x)", l->node, b.valid,
                  b.app_crc);
        return EXIT_REJECTED;
    }
    const double limit = (double)bitrate / 8.0; /* B/s: the image's bits alone */
    const double bus_s = bus_bits / (double)bitrate;
    const double took = wall > bus_s ? wall : bus_s;
    printf("verified: application %d.%d.%d, crc 0x%08x\n", b.app_major, b.app_minor, b.app_patch, b.app_crc);
    printf("transfer: %u bytes in %.3f s on the wall clock (%.0f B/s); its frames need %.3f s of a %ld bit/s bus, "
           "stuff bits counted (%.0f B/s)\n",
           image_len, wall, image_len / wall, bus_s, bitrate, image_len / bus_s);
    printf("rate: %.0f B/s, %.1f %% of the bus's limit (%ld bit/s / 8 = %.0f B/s: %.3f s for the image's bits "
           "alone)\n",
           image_len / took, 100.0 * image_len / took / limit, bitrate, limit, image_len / limit);
    if (no_start) {
        printf("node %u stays in its bootloader (--no-start)\n", l->node);
        return EXIT_OK;
    }
    const int32_t go[1] = {4};
    if ((rc = link_send(l, PM_BOOT_START, go) == 0 ? answered(l, PM_BOOT_START, 4, &a) : EXIT_BUS) != EXIT_OK)
        return rc;
    printf("node %u starts application %d.%d.%d\n", l->node, b.app_major, b.app_minor, b.app_patch);
    return EXIT_OK;
}
