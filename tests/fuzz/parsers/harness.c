/* What the parser cases share: the input as a file in memory, a quiet stderr, and the shape of a
 * refusal's message (checks.h). */
#define _GNU_SOURCE /* memfd_create */
#include <ctype.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

#include "checks.h"
#include "fuzz_target.h"

const char *mem_file(const char *data, size_t size)
{
    static int fd = -1;
    static char path[64];
    if (fd < 0) {
        fd = memfd_create("fuzz_parsers_input", 0);
        FUZZ_CHECK(fd >= 0);
        snprintf(path, sizeof path, "/proc/self/fd/%d", fd);
    }
    FUZZ_CHECK(ftruncate(fd, 0) == 0);
    size_t done = 0;
    while (done < size) {
        const ssize_t w = pwrite(fd, data + done, size - done, (off_t)done);
        FUZZ_CHECK(w > 0);
        done += (size_t)w;
    }
    return path;
}

void without_stderr(void (*fn)(void *), void *arg)
{
    static int devnull = -1;
    if (devnull < 0) {
        devnull = open("/dev/null", O_WRONLY);
        FUZZ_CHECK(devnull >= 0);
    }
    fflush(stderr);
    const int saved = dup(2);
    FUZZ_CHECK(saved >= 0 && dup2(devnull, 2) == 2);
    fn(arg);
    fflush(stderr);
    FUZZ_CHECK(dup2(saved, 2) == 2);
    close(saved);
}

int message_line(const char *err, size_t cap, const char *name)
{
    FUZZ_CHECK(memchr(err, '\0', cap) != NULL);
    const size_t n = strlen(name);
    FUZZ_CHECK(strlen(err) > n + 2);
    FUZZ_CHECK(!strncmp(err, name, n) && err[n] == ':');
    const char *p = err + n + 1;
    if (*p == ' ')
        return 0;
    FUZZ_CHECK(isdigit((unsigned char)*p) && *p != '0');
    long line = 0;
    while (isdigit((unsigned char)*p) && line < 100000000)
        line = line * 10 + (*p++ - '0');
    FUZZ_CHECK(p[0] == ':' && p[1] == ' ' && p[2] != '\0');
    return (int)line;
}
