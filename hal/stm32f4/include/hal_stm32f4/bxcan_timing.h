/* Bit timing of the bxCAN (RM0090 32.7.7): from the peripheral clock and a bit rate to the BTR
 * fields, and back.
 *
 * A bit is 1 + TS1 + TS2 time quanta of (BRP + 1) / pclk each (the register fields hold value
 * minus one); the sample point falls after 1 + TS1 quanta.  bxcan_timing_compute() promises:
 * - the exact bit rate (pclk = bitrate x quanta x prescaler in integers) or an error, never a
 *   nearby rate;
 * - 8..25 quanta per bit, TS1 1..16, TS2 1..8, prescaler 1..1024;
 * - the sample point nearest CiA 301's recommended 87.5 % among those configurations, and within
 *   CiA 301's valid range: 85..90 % below 800 kbit/s, 75..90 % at 800 kbit/s and above (few
 *   quanta per bit at high rates), or an error;
 * - on a tie, more quanta per bit (a finer resynchronisation step);
 * - SJW = min(4, TS2) quanta, the widest jump the phase segments allow, for the most tolerance
 *   to oscillator mismatch between nodes.
 * Plain arithmetic: no register access. */
#ifndef TSE_BXCAN_TIMING_H
#define TSE_BXCAN_TIMING_H

#include <stdbool.h>
#include <stdint.h>

typedef enum {
    BXCAN_TIMING_OK = 0,
    BXCAN_TIMING_BAD_ARG,      /* a zero clock or bit rate */
    BXCAN_TIMING_INEXACT,      /* no prescaler and 8..25 quanta give the bit rate exactly */
    BXCAN_TIMING_SAMPLE_POINT, /* exact rates exist, but none with a sample point in range */
} bxcan_timing_status;

/* Computes the BTR value (timing fields only: loop-back and silent modes off) into *btr. */
bxcan_timing_status bxcan_timing_compute(uint32_t pclk_hz, uint32_t bitrate, uint32_t *btr);

const char *bxcan_timing_str(bxcan_timing_status s);

/* A BTR value decoded, for diagnostics. */
typedef struct {
    uint32_t prescaler;       /* BRP + 1 */
    uint32_t ts1, ts2, sjw;   /* in time quanta (field + 1) */
    uint32_t quanta;          /* per bit: 1 + ts1 + ts2 */
    uint32_t bitrate_hz;      /* pclk / (prescaler x quanta), rounded to nearest */
    bool bitrate_exact;       /* the division above has no remainder */
    uint32_t sample_point_bp; /* sample point in basis points (8750 = 87.50 %), rounded */
} bxcan_btr_info;

/* Decodes btr as the hardware reads it at peripheral clock pclk_hz (not zero). */
bxcan_btr_info bxcan_btr_decode(uint32_t btr, uint32_t pclk_hz);

#endif
