#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "hal_posix/posix_hal.h"

static uint64_t now_us(void *ctx)
{
    (void)ctx;
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (uint64_t)t.tv_sec * 1000000u + (uint64_t)t.tv_nsec / 1000u;
}

hal_clock posix_clock_hal(void)
{
    return (hal_clock){NULL, now_us};
}

static int load(void *ctx, void *buf, size_t cap)
{
    const posix_storage *s = ctx;
    if (!s->path)
        return 0;
    FILE *f = fopen(s->path, "rb");
    if (!f)
        return errno == ENOENT ? 0 : -1;
    const size_t n = fread(buf, 1, cap, f);
    const int bad = ferror(f);
    fclose(f);
    return bad ? -1 : (int)n;
}

/* Written to a temporary file and renamed over the old one: a crash never leaves half a record. */
static int save(void *ctx, const void *buf, size_t len)
{
    const posix_storage *s = ctx;
    if (!s->path)
        return -1;
    char tmp[4096];
    if (snprintf(tmp, sizeof tmp, "%s.tmp", s->path) >= (int)sizeof tmp)
        return -1;
    FILE *f = fopen(tmp, "wb");
    if (!f)
        return -1;
    const int ok = fwrite(buf, 1, len, f) == len && fflush(f) == 0 && fsync(fileno(f)) == 0;
    if (fclose(f) != 0 || !ok || rename(tmp, s->path) != 0) {
        remove(tmp);
        return -1;
    }
    return 0;
}

hal_storage posix_storage_hal(posix_storage *s)
{
    return (hal_storage){s, load, save};
}
