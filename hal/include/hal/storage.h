/* Non-volatile storage for one parameter record (flash sector on the board, a file on the host).
 * The firmware adds its own version and CRC; the storage only keeps bytes. */
#ifndef HAL_STORAGE_H
#define HAL_STORAGE_H

#include <stddef.h>

typedef struct {
    void *ctx;
    /* Reads up to cap bytes of the stored record.  Returns its length, 0 if nothing is stored,
     * -1 on an error. */
    int (*load)(void *ctx, void *buf, size_t cap);
    /* Replaces the stored record.  Returns 0, or -1 on an error (the old record then survives). */
    int (*save)(void *ctx, const void *buf, size_t len);
} hal_storage;

#endif
