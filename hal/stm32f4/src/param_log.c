/* The parameter log of param_log.h: scanning the sectors, appending a record, starting a
 * sector. */
#include "hal_stm32f4/param_log.h"

#include <string.h>

#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#error "the log's layout is defined in little-endian words"
#endif

#define BLANK 0xFFFFFFFFu
#define MAX_RECORD_WORDS PARAM_LOG_RECORD_WORDS(PARAM_LOG_MAX_PAYLOAD)

/* CRC-32 of IEEE 802.3, four bits a step: 16 table entries (the polynomial 0xEDB88320 applied
 * to each nibble) instead of 256, so that the table costs 64 bytes of flash. */
static const uint32_t crc_nibble[16] = {
    0x00000000u, 0x1DB71064u, 0x3B6E20C8u, 0x26D930ACu, 0x76DC4190u, 0x6B6B51F4u,
    0x4DB26158u, 0x5005713Cu, 0xEDB88320u, 0xF00F9344u, 0xD6D6A3E8u, 0xCB61B38Cu,
    0x9B64C2B0u, 0x86D3D2D4u, 0xA00AE278u, 0xBDBDF21Cu,
};

static uint32_t crc_words(const uint32_t *w, uint32_t n)
{
    const uint8_t *p = (const uint8_t *)w;
    uint32_t crc = 0xFFFFFFFFu;
    for (uint32_t i = 0; i < 4u * n; ++i) {
        crc ^= p[i];
        crc = (crc >> 4) ^ crc_nibble[crc & 0xFu];
        crc = (crc >> 4) ^ crc_nibble[crc & 0xFu];
    }
    return ~crc;
}

static uint32_t sector_words(const param_log *log)
{
    return log->flash.sector_bytes / 4u;
}

static const uint32_t *sector_mem(const param_log *log, int s)
{
    return log->flash.mem + (uint32_t)s * sector_words(log);
}

/* A record's first word carries its length twice, once inverted: a word torn while being
 * programmed keeps some 1 bits that should have become 0, which breaks the pair, so a torn
 * first word is never taken for a length. */
static uint32_t len_word(uint32_t len)
{
    return len | (~len & 0xFFFFu) << 16;
}

/* The payload length a record's first word announces, or 0 if w is no record's first word. */
static uint32_t announced_len(uint32_t w)
{
    const uint32_t len = w & 0xFFFFu;
    if (w != len_word(len) || len == 0 || len > PARAM_LOG_MAX_PAYLOAD)
        return 0;
    return len;
}

static bool header_valid(const uint32_t *h)
{
    return h[0] == PARAM_LOG_MAGIC && h[2] == PARAM_LOG_FORMAT && h[3] == crc_words(h, 3);
}

static bool words_equal(const uint32_t *a, const uint32_t *b, uint32_t n)
{
    for (uint32_t i = 0; i < n; ++i)
        if (a[i] != b[i])
            return false;
    return true;
}

/* Walks a whole sector.  A valid record is skipped as a whole; anything else (a torn record,
 * planted garbage, the leftovers of a half-done erase) is stepped over one word at a time, so
 * that the records after it are still found. */
static void scan_sector(const param_log *log, int s, param_log_sector *out)
{
    const uint32_t *m = sector_mem(log, s);
    const uint32_t n = sector_words(log);
    out->header_ok = header_valid(m);
    out->generation = m[1];
    out->has_newest = false;
    out->newest_seq = 0;
    out->newest_pos = 0;
    out->used_end = PARAM_LOG_HEADER_WORDS;
    uint32_t p = PARAM_LOG_HEADER_WORDS;
    while (p < n) {
        if (m[p] == BLANK) {
            ++p;
            continue;
        }
        if (p + 1u > out->used_end)
            out->used_end = p + 1u;
        const uint32_t len = announced_len(m[p]);
        const uint32_t words = PARAM_LOG_RECORD_WORDS(len);
        if (len != 0 && words <= n - p) {
            /* Its later words may have been programmed to 0xFFFFFFFF, or torn and read so:
             * none of them is ever programmed again. */
            if (p + words > out->used_end)
                out->used_end = p + words;
            if (m[p + words - 1u] == crc_words(&m[p], words - 1u)) {
                if (!out->has_newest || m[p + 1u] > out->newest_seq) {
                    out->has_newest = true;
                    out->newest_seq = m[p + 1u];
                    out->newest_pos = p;
                }
                p += words;
                continue;
            }
        }
        ++p;
    }
}

static void scan(param_log *log)
{
    for (int s = 0; s < 2; ++s)
        scan_sector(log, s, &log->sec[s]);

    /* Sequence numbers never wrap in the flash's life (10,000 erases of about a thousand
     * records per sector), so the larger one is the newer. */
    log->newest = -1;
    for (int s = 0; s < 2; ++s) {
        const param_log_sector *c = &log->sec[s];
        if (!c->has_newest)
            continue;
        if (log->newest < 0 || c->newest_seq > log->sec[log->newest].newest_seq)
            log->newest = s;
    }

    /* Append only where the newest record is and the header is the latest one written: a
     * sector whose erase was cut short keeps an older header and older records, never both
     * the newest record and the highest generation. */
    log->active = -1;
    if (log->newest >= 0) {
        const param_log_sector *a = &log->sec[log->newest];
        const param_log_sector *b = &log->sec[1 - log->newest];
        if (a->header_ok && !(b->header_ok && b->generation >= a->generation)) {
            log->active = log->newest;
            /* A power cut may have torn the word after the last visible one and left it
             * reading 0xFFFFFFFF: leave that word alone. */
            log->write_pos = a->used_end + 1u;
        }
    }
    log->known = true;
}

/* Lays out the record of param_log.h in rec; returns its length in words. */
static uint32_t build_record(uint32_t *rec, uint32_t seq, const void *buf, size_t len)
{
    const uint32_t words = PARAM_LOG_RECORD_WORDS(len);
    rec[0] = len_word((uint32_t)len);
    rec[1] = seq;
    rec[words - 2u] = BLANK; /* the padding of the last payload word */
    memcpy(&rec[2], buf, len);
    rec[words - 1u] = crc_words(rec, words - 1u);
    return words;
}

static int program_verified(param_log *log, int s, uint32_t pos, const uint32_t *w, uint32_t n)
{
    const uint32_t offset = ((uint32_t)s * sector_words(log) + pos) * 4u;
    if (log->flash.program(log->flash.ctx, offset, w, n) != FLASH_OPS_OK)
        return -1;
    return words_equal(&sector_mem(log, s)[pos], w, n) ? 0 : -1;
}

static void note_newest(param_log *log, int s, uint32_t pos, uint32_t seq, uint32_t words)
{
    param_log_sector *c = &log->sec[s];
    c->has_newest = true;
    c->newest_seq = seq;
    c->newest_pos = pos;
    c->used_end = pos + words;
    log->newest = s;
    log->active = s;
    log->write_pos = pos + words;
}

static int append(param_log *log, const uint32_t *rec, uint32_t words)
{
    const int s = log->active;
    const uint32_t pos = log->write_pos;
    if (program_verified(log, s, pos, rec, words) != 0)
        return -1;
    note_newest(log, s, pos, rec[1], words);
    return 0;
}

/* Erases sector s (which does not hold the newest good record), checks it blank, writes its
 * header and then the record.  Until the record's last word is written the newest good
 * record stays the one in the other sector. */
static int start_sector(param_log *log, int s, const uint32_t *rec, uint32_t words)
{
    uint32_t generation = 0;
    for (int i = 0; i < 2; ++i)
        if (log->sec[i].header_ok && log->sec[i].generation > generation)
            generation = log->sec[i].generation;
    ++generation;

    /* From here on the scan's view of sector s is void, whatever happens. */
    log->sec[s].header_ok = false;
    log->sec[s].has_newest = false;
    if (log->flash.erase(log->flash.ctx, (uint32_t)s) != FLASH_OPS_OK)
        return -1;
    const uint32_t *m = sector_mem(log, s);
    for (uint32_t i = 0; i < sector_words(log); ++i)
        if (m[i] != BLANK)
            return -1; /* worn out, or the erase did not happen */

    uint32_t header[PARAM_LOG_HEADER_WORDS] = {PARAM_LOG_MAGIC, generation, PARAM_LOG_FORMAT, 0};
    header[3] = crc_words(header, 3);
    if (program_verified(log, s, 0, header, PARAM_LOG_HEADER_WORDS) != 0)
        return -1;
    log->sec[s].header_ok = true;
    log->sec[s].generation = generation;
    if (program_verified(log, s, PARAM_LOG_HEADER_WORDS, rec, words) != 0)
        return -1;
    note_newest(log, s, PARAM_LOG_HEADER_WORDS, rec[1], words);
    return 0;
}

int param_log_init(param_log *log, flash_ops flash)
{
    memset(log, 0, sizeof *log);
    log->newest = -1;
    log->active = -1;
    if (!flash.mem || !flash.erase || !flash.program || flash.sector_bytes % 4u != 0 ||
        flash.sector_bytes > 0x40000000u ||
        flash.sector_bytes / 4u < PARAM_LOG_HEADER_WORDS + MAX_RECORD_WORDS)
        return -1;
    log->flash = flash;
    return 0;
}

int param_log_load(param_log *log, void *buf, size_t cap)
{
    /* The cached position is checked again before it is trusted; if the flash no longer
     * holds it, one fresh scan decides. */
    for (int attempt = 0; attempt < 2; ++attempt) {
        if (!log->known)
            scan(log);
        if (log->newest < 0)
            return 0;
        const param_log_sector *c = &log->sec[log->newest];
        const uint32_t *r = &sector_mem(log, log->newest)[c->newest_pos];
        const uint32_t len = announced_len(r[0]);
        const uint32_t words = PARAM_LOG_RECORD_WORDS(len);
        if (len != 0 && c->newest_pos + words <= sector_words(log) && r[1] == c->newest_seq &&
            r[words - 1u] == crc_words(r, words - 1u)) {
            if (len > cap)
                return -1;
            memcpy(buf, &r[2], len);
            return (int)len;
        }
        log->known = false;
    }
    return -1;
}

int param_log_save(param_log *log, const void *buf, size_t len)
{
    if (len == 0 || len > PARAM_LOG_MAX_PAYLOAD)
        return -1;
    if (!log->known)
        scan(log);
    uint32_t seq = 1;
    if (log->newest >= 0) {
        if (log->sec[log->newest].newest_seq >= UINT32_MAX - 1u)
            return -1; /* beyond the flash's life: see scan */
        seq = log->sec[log->newest].newest_seq + 1u;
    }

    uint32_t rec[MAX_RECORD_WORDS];
    uint32_t words = build_record(rec, seq, buf, len);
    if (log->active >= 0 && log->write_pos <= sector_words(log) - words) {
        if (append(log, rec, words) == 0)
            return 0;
        /* The program failed or read back wrong.  Rather than guess which words it touched,
         * start the other sector.  The failed record may still have become valid: the retry
         * takes the next sequence number so that the two never tie. */
        words = build_record(rec, seq + 1u, buf, len);
    }
    const int target = log->newest >= 0 ? 1 - log->newest : 0;
    if (start_sector(log, target, rec, words) == 0)
        return 0;
    log->known = false;
    return -1;
}

static int hal_load(void *ctx, void *buf, size_t cap)
{
    return param_log_load(ctx, buf, cap);
}

static int hal_save(void *ctx, const void *buf, size_t len)
{
    return param_log_save(ctx, buf, len);
}

hal_storage param_log_hal(param_log *log)
{
    return (hal_storage){log, hal_load, hal_save};
}
