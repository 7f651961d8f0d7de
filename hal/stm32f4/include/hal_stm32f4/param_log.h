/* The board's parameter storage: a log of records in two flash sectors, behind hal_storage.
 *
 * Promise: a power cut at any moment of a save never loses the previous good record.  After
 * the cut, load returns either that record or the one being saved, never anything else.
 *
 * How:
 * - Records are only ever appended, each with a sequence number and a CRC written last: a
 *   torn record fails its CRC and is skipped.  load returns the valid record with the highest
 *   sequence number in either sector.
 * - When the sector holding the newest record is full, save erases the other sector, writes a
 *   header and the new record there, and only then is the old sector stale.  The sector
 *   holding the newest good record is never erased.
 * - A sector is only ever appended to if it holds the newest record and has the highest
 *   generation: any other sector (older, half-erased by a power cut, never formatted) is
 *   erased again, and checked blank, before it is written.
 * - After a reset the first append leaves one blank word after the last written one: a word
 *   torn by a power cut may read 0xFFFFFFFF yet be half programmed, and is not programmed
 *   again.  One case escapes this: when the first program after a reset is itself torn with
 *   no bit showing, the next boot sees what the previous one saw and programs that same word
 *   again.  The F405 accepts it (RM0090 3.5.4: bits may be cleared again) and the read-back
 *   decides; a flash that refuses it fails the append.  Any failed or wrongly read-back
 *   append makes save start the other sector instead, so the save still succeeds and the
 *   previous record is never touched.
 *
 * Layout (all words little-endian, as they lie in flash):
 *   sector header, 4 words: PARAM_LOG_MAGIC, generation, PARAM_LOG_FORMAT, CRC of the three;
 *   then records, one after another from word 4 (blank words may separate them):
 *     word 0: len | (~len & 0xFFFF) << 16, len = payload bytes, 1..PARAM_LOG_MAX_PAYLOAD
 *     word 1: sequence number
 *     payload, padded with 0xFF bytes to whole words
 *     last word: CRC of all the record's words before it.
 * CRC: CRC-32 of IEEE 802.3 (reflected polynomial 0xEDB88320, initial value and final xor
 * 0xFFFFFFFF) over the bytes in flash order.  A record of n payload bytes takes
 * 4 * (3 + ceil(n / 4)) bytes: 160 bytes for the firmware's 146-byte parameter record (34
 * parameters), of which a 128 KiB sector holds 819 (a word fewer for each reset in between).
 *
 * Plain C over flash_ops: no register access, no heap.  Not reentrant: one caller at a time. */
#ifndef TSE_PARAM_LOG_H
#define TSE_PARAM_LOG_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "hal/storage.h"
#include "hal_stm32f4/flash_ops.h"

/* The size of the log's sectors on every board so far: two 128 KiB sectors (RM0090 table 5),
 * which ones the board description says (board_desc.h: 10 and 11 on a 1 MiB part, 6 and 7 on
 * 512 KiB); the linker script keeps the image below them. */
#define PARAM_LOG_SECTOR_BYTES 0x20000u /* 128 KiB */

#define PARAM_LOG_MAX_PAYLOAD 256u
#define PARAM_LOG_MAGIC 0x4C505354u /* "TSPL" in flash order */
#define PARAM_LOG_FORMAT 1u
#define PARAM_LOG_HEADER_WORDS 4u
/* Words of a record of n payload bytes. */
#define PARAM_LOG_RECORD_WORDS(n) (3u + ((uint32_t)(n) + 3u) / 4u)

/* What a scan found in one sector.  Private to param_log.c. */
typedef struct {
    bool header_ok;
    bool has_newest;
    uint32_t generation;
    uint32_t newest_seq;
    uint32_t newest_pos; /* word index of that record in the sector */
    uint32_t used_end;   /* one past the last word that may have been programmed */
} param_log_sector;

typedef struct {
    flash_ops flash;
    /* Private: what the last scan found, kept up to date by save.  `known` is cleared by a
     * failed flash operation: the next load or save scans again. */
    bool known;
    int newest; /* sector holding the newest good record, -1 if none */
    int active; /* sector to append to, -1 if the next save starts a sector */
    uint32_t write_pos;
    param_log_sector sec[2];
} param_log;

/* Binds the log to its flash (the ops are copied; their ctx must outlive the log).  Returns
 * 0, or -1 if the sectors cannot hold a header and a largest record.  Reads and writes
 * nothing yet. */
int param_log_init(param_log *log, flash_ops flash);

/* The newest good record: copies it to buf and returns its length; 0 if there is none; -1 if
 * it is longer than cap. */
int param_log_load(param_log *log, void *buf, size_t cap);

/* Appends a record of len bytes (1..PARAM_LOG_MAX_PAYLOAD), starting a sector when needed.
 * Returns 0, or -1 (bad length, or a flash error: the previous record then survives). */
int param_log_save(param_log *log, const void *buf, size_t len);

hal_storage param_log_hal(param_log *log);

#endif
