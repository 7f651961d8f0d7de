#include "boot/layout.h"

#include <string.h>

/* RM0090 table 5: the F405/F407's 12 sectors of bank 1. */
static uint32_t f4_sector_bytes(unsigned k)
{
    return k < 4u ? 0x4000u : k == 4u ? 0x10000u : 0x20000u;
}

int boot_layout_stm32f4(boot_layout *l, unsigned boot_sectors, unsigned end_sector)
{
    memset(l, 0, sizeof *l);
    if (boot_sectors == 0 || end_sector <= boot_sectors || end_sector > 12u ||
        end_sector - boot_sectors > BOOT_LAYOUT_MAX_SECTORS)
        return -1;
    uint32_t at = 0;
    for (unsigned k = 0; k < boot_sectors; ++k)
        at += f4_sector_bytes(k);
    l->flash_base = 0x08000000u;
    l->boot_bytes = at;
    l->boot_sectors = (uint8_t)boot_sectors;
    l->app_offset = at;
    for (unsigned k = boot_sectors; k < end_sector; ++k) {
        boot_sector *s = &l->sectors[l->nsectors++];
        s->offset = at;
        s->bytes = f4_sector_bytes(k);
        s->number = (uint8_t)k;
        at += s->bytes;
    }
    l->app_bytes = at - l->app_offset;
    return 0;
}

int boot_layout_check(const boot_layout *l)
{
    if (l->nsectors == 0 || l->nsectors > BOOT_LAYOUT_MAX_SECTORS || l->app_offset < l->boot_bytes)
        return -1;
    uint32_t at = l->app_offset;
    for (unsigned i = 0; i < l->nsectors; ++i) {
        const boot_sector *s = &l->sectors[i];
        if (s->offset != at || s->bytes == 0 || s->number < l->boot_sectors ||
            (i > 0 && s->number <= l->sectors[i - 1].number))
            return -1;
        at += s->bytes;
    }
    return at - l->app_offset == l->app_bytes ? 0 : -1;
}

unsigned boot_layout_sectors_for(const boot_layout *l, uint32_t length)
{
    if (length == 0 || length > l->app_bytes)
        return 0;
    uint32_t covered = 0;
    unsigned n = 0;
    while (covered < length)
        covered += l->sectors[n++].bytes;
    return n;
}
