#define _POSIX_C_SOURCE 200809L /* pread, pwrite, ftruncate */
#include "file_flash.h"

#include <errno.h>
#include <fcntl.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static int write_through(file_flash *f, uint32_t offset, uint32_t n)
{
    return pwrite(f->fd, f->mem + offset, n, (off_t)offset) == (ssize_t)n ? FLASH_OPS_OK : FLASH_OPS_EFAIL;
}

int file_flash_open(file_flash *f, const char *path, const boot_layout *layout)
{
    f->layout = layout;
    f->bytes = layout->app_offset + layout->app_bytes;
    if (f->bytes > FILE_FLASH_MAX_BYTES) {
        errno = EFBIG;
        return -1;
    }
    f->fd = open(path, O_RDWR | O_CREAT, 0644);
    if (f->fd < 0)
        return -1;
    struct stat st;
    if (fstat(f->fd, &st) != 0)
        return -1;
    if ((uint64_t)st.st_size == f->bytes)
        return pread(f->fd, f->mem, f->bytes, 0) == (ssize_t)f->bytes ? 0 : -1;
    /* A new board: the bootloader's sectors hold something (not ours to touch), the rest erased. */
    memset(f->mem, 0xFF, f->bytes);
    for (uint32_t i = 0; i < layout->boot_bytes; ++i)
        f->mem[i] = (uint8_t)(i * 7u + 1u);
    if (ftruncate(f->fd, 0) != 0 || write_through(f, 0, f->bytes) != FLASH_OPS_OK)
        return -1;
    return 0;
}

static int ff_erase(void *ctx, uint32_t sector)
{
    file_flash *f = ctx;
    const boot_layout *l = f->layout;
    for (unsigned i = 0; i < l->nsectors; ++i)
        if (l->sectors[i].number == sector) {
            memset(f->mem + l->sectors[i].offset, 0xFF, l->sectors[i].bytes);
            return write_through(f, l->sectors[i].offset, l->sectors[i].bytes);
        }
    return FLASH_OPS_EARG; /* the bootloader's, or none: the file's board has no other */
}

static int ff_program(void *ctx, uint32_t offset, const uint32_t *words, uint32_t n)
{
    file_flash *f = ctx;
    if (offset % 4u != 0 || offset > f->bytes || n > (f->bytes - offset) / 4u)
        return FLASH_OPS_EARG;
    for (uint32_t k = 0; k < n; ++k) {
        uint32_t w;
        memcpy(&w, f->mem + offset + 4u * k, 4);
        if ((words[k] & ~w) != 0)
            return FLASH_OPS_EFAIL; /* a bit from 0 to 1: the part cannot */
    }
    for (uint32_t k = 0; k < n; ++k) {
        uint32_t w;
        memcpy(&w, f->mem + offset + 4u * k, 4);
        w &= words[k];
        memcpy(f->mem + offset + 4u * k, &w, 4);
    }
    return write_through(f, offset, 4u * n);
}

flash_ops file_flash_ops(file_flash *f)
{
    return (flash_ops){f, (const uint32_t *)(const void *)f->mem, 0, ff_erase, ff_program};
}
