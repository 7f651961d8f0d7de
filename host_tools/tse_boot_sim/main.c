/* tse-boot-sim: a board's bootloader on a SocketCAN bus (vcan0 in the tests), its flash a file.
 *
 * The same logic as the board's bootloader (boot/: the decision, the update, the bus), over the
 * STM32F405's layout (bootloader in sector 0, the application area in sectors 1..9) kept in
 * --flash FILE.  At start it decides as the board does: with a whole image for --board in the file
 * and no --stay, it says which application it would start and exits 0 ("the application starts");
 * otherwise it stays on the bus as node --node and takes an update, until BOOT_START (it then says
 * which application starts and exits 0), or SIGINT/SIGTERM (exit 0).  Erases take no time here;
 * the board's do (docs/protocol.md, Updating the firmware). */
#define _POSIX_C_SOURCE 200809L /* poll, signal */
#include <errno.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "boot/bus.h"
#include "boot/decide.h"
#include "boot/image.h"
#include "file_flash.h"
#include "hal_posix/posix_hal.h"
#include "tse_version.h"

static volatile sig_atomic_t stop_now;

static void on_signal(int sig)
{
    (void)sig;
    stop_now = 1;
}

static int usage(FILE *out, int rc)
{
    fprintf(out, "usage: tse-boot-sim --flash FILE [--iface IF] [--node N] [--board NAME] [--stay]\n"
                 "  --flash FILE  the board's flash (created erased, with a bootloader's sector, if missing)\n"
                 "  --iface IF    SocketCAN interface (default vcan0)\n"
                 "  --node N      node 1..15 (default 1)\n"
                 "  --board NAME  the board's name, whose CRC-32 an image must carry (default tse-sim)\n"
                 "  --stay        as after BOOT_ENTER: stay in the bootloader even with a valid image\n"
                 "  --drop N      lose the Nth frame it receives (1: the first), as an overrun would\n");
    return rc;
}

static void say_start(const boot_image_header *h)
{
    printf("tse-boot-sim: starting the application %u.%u.%u (%u bytes, crc 0x%08x)\n", (h->version >> 16) & 0xFFu,
           (h->version >> 8) & 0xFFu, h->version & 0xFFu, h->length, h->crc);
    fflush(stdout);
}

static file_flash flash;

int main(int argc, char **argv)
{
    const char *path = NULL, *iface = "vcan0", *board_name = "tse-sim";
    long node = 1, drop = 0;
    int stay = 0;
    for (int i = 1; i < argc; ++i) {
        const int more = i + 1 < argc;
        if (!strcmp(argv[i], "--flash") && more)
            path = argv[++i];
        else if (!strcmp(argv[i], "--iface") && more)
            iface = argv[++i];
        else if (!strcmp(argv[i], "--board") && more)
            board_name = argv[++i];
        else if (!strcmp(argv[i], "--node") && more) {
            char *end;
            node = strtol(argv[++i], &end, 10);
            if (*end || node < 1 || node > 15) {
                fprintf(stderr, "tse-boot-sim: --node takes 1..15: %s\n", argv[i]);
                return 2;
            }
        } else if (!strcmp(argv[i], "--drop") && more) {
            char *end;
            drop = strtol(argv[++i], &end, 10);
            if (*end || drop < 1) {
                fprintf(stderr, "tse-boot-sim: --drop takes a frame count from 1: %s\n", argv[i]);
                return 2;
            }
        } else if (!strcmp(argv[i], "--stay"))
            stay = 1;
        else if (!strcmp(argv[i], "--version")) {
            printf("tse-boot-sim %s (bootloader %d.%d)\n", TSE_VERSION, BOOT_VERSION_MAJOR, BOOT_VERSION_MINOR);
            return 0;
        } else if (!strcmp(argv[i], "--help"))
            return usage(stdout, 0);
        else {
            fprintf(stderr, "tse-boot-sim: unknown or incomplete option: %s\n", argv[i]);
            return usage(stderr, 2);
        }
    }
    if (!path) {
        fprintf(stderr, "tse-boot-sim: --flash FILE is needed\n");
        return usage(stderr, 2);
    }
    static boot_layout layout;
    boot_layout_stm32f4(&layout, 1, 10);
    if (file_flash_open(&flash, path, &layout) != 0) {
        fprintf(stderr, "tse-boot-sim: %s: %s\n", path, strerror(errno));
        return 1;
    }
    const flash_ops ops = file_flash_ops(&flash);
    const uint32_t board = boot_board_id(board_name);
    boot_image_status why;
    boot_image_header h;
    if (boot_decide(&layout, flash.mem, board, stay, &why, &h) == BOOT_START_APP) {
        say_start(&h);
        return 0;
    }
    posix_can can;
    if (posix_can_open(&can, iface, (uint8_t)node) != 0) {
        fprintf(stderr, "tse-boot-sim: %s: %s\n", iface, strerror(errno));
        return 1;
    }
    (void)signal(SIGINT, on_signal); /* SIG_ERR only for a bad signal number */
    (void)signal(SIGTERM, on_signal);
    static boot_bus bus;
    boot_bus_init(&bus, &layout, &ops, board, (uint8_t)node, posix_can_hal(&can));
    printf("tse-boot-sim: node %ld, board %s (0x%08x), in the bootloader (%s; application: %s)\n", node, board_name,
           board, stay ? "asked to stay" : "no application to start", boot_image_status_name(why));
    fflush(stdout);
    const hal_can hc = posix_can_hal(&can);
    long received = 0;
    while (!stop_now && !bus.start) {
        hal_can_frame f;
        if (hc.receive(hc.ctx, &f) == 1) {
            if (++received == drop) {
                printf("tse-boot-sim: frame %ld (id 0x%03x) lost (--drop)\n", received, f.id);
                fflush(stdout);
                continue;
            }
            boot_bus_frame(&bus, &f);
            continue;
        }
        struct pollfd p = {can.fd, POLLIN, 0};
        (void)poll(&p, 1, 50);
    }
    if (bus.start) {
        boot_decide(&layout, flash.mem, board, false, &why, &h);
        say_start(&h);
    }
    posix_can_close(&can);
    return 0;
}
