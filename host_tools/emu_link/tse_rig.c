/* tse-rig: reads and drives the emulated board's rig (docs/emulator.md): the six slides with
 * their step counts, the homing switches, the e-stop chain, the bus's error state, a power cycle.
 *
 *   tse-rig [--rig PATH] [--timeout S] REQUEST...
 *
 * PATH (default $TSE_RIG) is the rig channel: the UNIX socket the emulator serves, or the
 * character device that leads to it in the harness's VM.  A request is checked before the channel
 * is touched (exit 2 naming what is wrong); the answer's lines are printed, and the exit status is
 * 0 for `ok`, 1 for `error: WHY` (WHY on stderr) or a channel that cannot be used, 4 when no
 * answer came in time. */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include <errno.h>
#include <stdbool.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "endpoint.h"

static const char *const help =
    "usage: tse-rig [--rig PATH] [--timeout S] REQUEST\n"
    "requests:\n"
    "  slides                      the six slide positions, metres (A1 B1 A2 B2 A3 B3)\n"
    "  steps                       the six step counts\n"
    "  time                        the emulator's virtual time, ns\n"
    "  log                         what the rig flagged (short STEP pulses, DIR set-up), one line each\n"
    "  firststep                   when the controller took the last MOVE_COMMIT, and the first STEP\n"
    "                              edge after it (virtual ns; -1: none)\n"
    "  feedgap                     the longest time between two watchdog reloads (the longest pause\n"
    "                              of the image's main loop) since the last feedgap, and how many\n"
    "  flashops                    the flash erase and program operations since the emulator started\n"
    "  cutflash N|off              a power cycle as the Nth flash operation from now starts (1..1e9)\n"
    "  estop open|closed           the e-stop chain\n"
    "  switch K open|closed|auto   slide K's (1..6) homing switch forced, or from its position\n"
    "  canerr on|off               the bus held in error (bus-off), or released\n"
    "  reset                       a power cycle (the flash and the slides are kept)\n"
    "PATH defaults to $TSE_RIG: the rig's UNIX socket, or the device that leads to it.\n";

static int usage_error(const char *what, const char *arg)
{
    fprintf(stderr, "tse-rig: %s%s%s\n%s", what, arg ? ": " : "", arg ? arg : "", help);
    return 2;
}

static int one_of(const char *s, const char *a, const char *b, const char *c)
{
    return !strcmp(s, a) || !strcmp(s, b) || (c && !strcmp(s, c));
}

/* Checks a request's words; returns 0 or an exit status (printed). */
static int check(int n, char **w)
{
    const char *r = w[0];
    if (one_of(r, "slides", "steps", "time") || one_of(r, "log", "reset", "flashops") ||
        one_of(r, "firststep", "feedgap", NULL))
        return n == 1 ? 0 : usage_error("takes no argument", r);
    if (!strcmp(r, "estop"))
        return n == 2 && one_of(w[1], "open", "closed", NULL) ? 0 : usage_error("estop takes open or closed", NULL);
    if (!strcmp(r, "canerr"))
        return n == 2 && one_of(w[1], "on", "off", NULL) ? 0 : usage_error("canerr takes on or off", NULL);
    if (!strcmp(r, "cutflash")) {
        const bool count = n == 2 && w[1][0] && strlen(w[1]) <= 9 && strspn(w[1], "0123456789") == strlen(w[1]) &&
                           strtol(w[1], NULL, 10) >= 1;
        return count || (n == 2 && !strcmp(w[1], "off")) ? 0 : usage_error("cutflash takes a count 1..999999999 or off", NULL);
    }
    if (!strcmp(r, "switch")) {
        if (n != 3 || strlen(w[1]) != 1 || w[1][0] < '1' || w[1][0] > '6')
            return usage_error("switch takes a slide 1..6 and open, closed or auto", NULL);
        return one_of(w[2], "open", "closed", "auto") ? 0 : usage_error("switch takes open, closed or auto", w[2]);
    }
    return usage_error("unknown request", r);
}

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + (double)t.tv_nsec * 1e-9;
}

int main(int argc, char **argv)
{
    const char *path = getenv("TSE_RIG");
    double timeout = 30.0;
    int i = 1;
    for (; i < argc && argv[i][0] == '-'; ++i) {
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h"))
            return fputs(help, stdout), 0;
        if (!strcmp(argv[i], "--rig") && i + 1 < argc) {
            path = argv[++i];
        } else if (!strcmp(argv[i], "--timeout") && i + 1 < argc) {
            char *end;
            timeout = strtod(argv[++i], &end);
            if (*end || !(timeout > 0 && timeout <= 3600))
                return usage_error("--timeout takes 0 to 3600 seconds", argv[i]);
        } else {
            return usage_error("unknown option", argv[i]);
        }
    }
    if (i >= argc)
        return usage_error("a request is needed", NULL);
    const int bad = check(argc - i, argv + i);
    if (bad)
        return bad;
    char req[128];
    size_t used = 0;
    for (int k = i; k < argc; ++k) {
        const int w = snprintf(req + used, sizeof req - used, "%s%s", argv[k], k + 1 < argc ? " " : "\n");
        if (w < 0 || (size_t)w >= sizeof req - used)
            return usage_error("the request is too long", argv[i]);
        used += (size_t)w;
    }
    if (!path || !*path)
        return usage_error("no rig channel: give --rig PATH or set TSE_RIG", NULL);
    const int fd = endpoint_open(path);
    if (fd < 0)
        return fprintf(stderr, "tse-rig: cannot open the rig channel %s: %s\n", path, strerror(errno)), 1;

    /* What an earlier, interrupted tse-rig left unread is not this request's answer. */
    char buf[4096];
    for (struct pollfd p = {fd, POLLIN, 0}; poll(&p, 1, 0) > 0 && (p.revents & POLLIN);)
        if (read(fd, buf, sizeof buf) <= 0)
            break;

    if (endpoint_write_all(fd, req, strlen(req)) != 0)
        return fprintf(stderr, "tse-rig: cannot write to the rig channel %s: %s\n", path, strerror(errno)), 1;

    /* The answer: lines up to "ok" or "error: ...". */
    const double end = now_s() + timeout;
    char line[512] = "";
    size_t len = 0;
    for (;;) {
        const double left = end - now_s();
        if (left <= 0)
            return fprintf(stderr, "tse-rig: no answer to '%s' within %g s (is the emulator running?)\n", argv[i],
                           timeout),
                   4;
        struct pollfd p = {fd, POLLIN, 0};
        if (poll(&p, 1, (int)(left * 1000) + 1) <= 0)
            continue;
        char c;
        const ssize_t n = read(fd, &c, 1);
        if (n <= 0)
            return fprintf(stderr, "tse-rig: the rig channel %s closed\n", path), 1;
        if (c == '\r')
            continue;
        if (c != '\n') {
            if (len + 1 < sizeof line)
                line[len++] = c;
            continue;
        }
        line[len] = 0;
        len = 0;
        if (!strcmp(line, "ok"))
            return 0;
        if (!strncmp(line, "error:", 6))
            return fprintf(stderr, "tse-rig: %s: %s\n", argv[i], line[6] == ' ' ? line + 7 : line + 6), 1;
        if (!strcmp(argv[i], "log") && !strcmp(line, "end"))
            continue; /* the log's own end, not one of its lines */
        puts(line);
        fflush(stdout);
    }
}
