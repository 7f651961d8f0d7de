/* A simulated NOR flash behind flash_ops: two equal sectors for the parameter log's tests, or a
 * device's sectors of their own sizes for the bootloader's (sim_flash_init_sectors).
 *
 * It keeps the rules of the real part and is stricter where the log must not lean on luck:
 * - erase sets a whole sector to 0xFFFFFFFF; program clears bits, a 32-bit word at a time;
 * - a word may be programmed once after an erase, and only if it is cleanly erased: a second
 *   program of the same word, a program that would turn a 0 bit into 1, or a program into a
 *   sector whose erase was cut short is refused (nothing written, FLASH_OPS_EFAIL, counted
 *   in `illegal`), as the controller's PGSERR would; the real F405 would accept some of them;
 * - the power can be cut at the N-th write operation (each word program and each sector
 *   erase is one operation).  The interrupted program leaves its word with a random subset
 *   of the bits it was clearing cleared (sometimes none, sometimes all); the interrupted erase
 *   leaves a random part of the sector erased, some words only partly, and the whole sector
 *   unfit for programming until erased again.  Every operation after the cut fails, without
 *   effect, until sim_flash_reboot.
 * Randomness comes from a seeded generator: a run is reproducible from its seed. */
#ifndef TSE_TEST_SIM_FLASH_H
#define TSE_TEST_SIM_FLASH_H

#include <stdbool.h>
#include <stdint.h>

#include "hal_stm32f4/flash_ops.h"

/* Room for the board's geometry: two sectors of 128 KiB; or the F405's sectors 0..5 (256 KiB). */
#define SIM_FLASH_MAX_SECTOR_BYTES 0x20000u
#define SIM_FLASH_MAX_WORDS (2u * SIM_FLASH_MAX_SECTOR_BYTES / 4u)
#define SIM_FLASH_MAX_SECTORS 12u

enum { SIM_WORD_ERASED, SIM_WORD_PROGRAMMED, SIM_WORD_UNSETTLED };

typedef struct {
    uint32_t words[SIM_FLASH_MAX_WORDS];
    uint8_t state[SIM_FLASH_MAX_WORDS]; /* SIM_WORD_*: what a program may do to the word */
    uint32_t sector_bytes;
    uint32_t rng;
    uint64_t ops;       /* write operations attempted while powered, the cut one included */
    uint64_t cut_at;    /* the value of ops at which the power goes; 0: never */
    bool dead;          /* the power went: everything fails until sim_flash_reboot */
    bool cut_happened;  /* a cut has taken place since sim_flash_cut_after was called */
    bool cut_in_erase;  /* ...and it interrupted an erase (else a word program) */
    uint32_t cut_word;  /* the word index of the interrupted program */
    uint32_t nsectors;                         /* sectors, in address order from word 0 */
    uint32_t sector_off[SIM_FLASH_MAX_SECTORS]; /* each one's first byte */
    uint32_t sector_len[SIM_FLASH_MAX_SECTORS]; /* and its bytes */
    uint32_t total_bytes;
    uint32_t erases[SIM_FLASH_MAX_SECTORS]; /* completed erases per sector */
    uint32_t programs;  /* completed word programs */
    uint32_t illegal;   /* programs refused as illegal */
} sim_flash;

/* Two sectors of sector_bytes (a multiple of 4, at most SIM_FLASH_MAX_SECTOR_BYTES), fresh
 * from the factory: erased. */
void sim_flash_init(sim_flash *f, uint32_t sector_bytes, uint32_t seed);

/* nsectors sectors of bytes[k] each (multiples of 4, SIM_FLASH_MAX_WORDS words in all at most),
 * erased; sector_bytes is bytes[0].  Returns 0, or -1 for a geometry that does not fit. */
int sim_flash_init_sectors(sim_flash *f, const uint32_t *bytes, uint32_t nsectors, uint32_t seed);

flash_ops sim_flash_ops(sim_flash *f);

/* The n-th write operation from now (1: the next one) is interrupted by a power cut. */
void sim_flash_cut_after(sim_flash *f, uint64_t n);

/* Power back: operations work again; the contents stay as the cut left them. */
void sim_flash_reboot(sim_flash *f);

/* Overwrites one byte behind the controller's back (bit rot, a stray write), leaving the
 * word's programming state alone. */
void sim_flash_poke(sim_flash *f, uint32_t byte_offset, uint8_t value);

#endif
