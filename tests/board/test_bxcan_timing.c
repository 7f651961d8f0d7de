/* bxCAN bit timing.  The BTR fields are decoded here with the reference manual's formula
 * (RM0090 32.7.7: tq = (BRP + 1) / pclk, bit = (1 + (TS1 + 1) + (TS2 + 1)) tq, sample point after
 * 1 + (TS1 + 1) tq), and checked against the requirements: the exact bit rate, 8..25 quanta,
 * the sample point inside CiA 301's range and as near 87.5 % as any exact configuration allows
 * (found here by brute force over every register value), SJW within the phase segments.
 * A few worked values are spelled out by hand. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>

#include "hal_stm32f4/bxcan_timing.h"

/* RM0090's BTR layout, written out here rather than taken from regs_can.h. */
typedef struct {
    uint32_t brp, ts1, ts2, sjw; /* actual values (field + 1) */
} fields;

static fields decode(uint32_t btr)
{
    const fields f = {(btr & 0x3FFu) + 1u, ((btr >> 16) & 0xFu) + 1u, ((btr >> 20) & 0x7u) + 1u,
                      ((btr >> 24) & 0x3u) + 1u};
    return f;
}

/* CiA 301: 75..90 % at 800 kbit/s and 1 Mbit/s, 85..90 % below. */
static double sp_low(uint32_t bitrate)
{
    return bitrate >= 800000u ? 0.75 : 0.85;
}

/* Distance from 87.5 % of the best exact configuration within range, or -1 if none; *any_exact
 * says whether any exact configuration (any sample point) exists. */
static double best_error(uint32_t pclk, uint32_t bitrate, int *any_exact)
{
    double best = -1.0;
    *any_exact = 0;
    for (uint32_t brp = 1; brp <= 1024; ++brp)
        for (uint32_t ts1 = 1; ts1 <= 16; ++ts1)
            for (uint32_t ts2 = 1; ts2 <= 8; ++ts2) {
                const uint32_t n = 1 + ts1 + ts2;
                if (n < 8 || n > 25 || (uint64_t)bitrate * brp * n != pclk)
                    continue;
                *any_exact = 1;
                const double sp = (double)(1 + ts1) / n;
                if (sp < sp_low(bitrate) - 1e-12 || sp > 0.90 + 1e-12)
                    continue;
                const double e = sp > 0.875 ? sp - 0.875 : 0.875 - sp;
                if (best < 0 || e < best)
                    best = e;
            }
    return best;
}

/* Everything a computed BTR must satisfy. */
static void check_btr(uint32_t pclk, uint32_t bitrate, uint32_t btr)
{
    const fields f = decode(btr);
    const uint32_t n = 1 + f.ts1 + f.ts2;
    assert_true(n >= 8 && n <= 25);
    assert_true((uint64_t)bitrate * f.brp * n == pclk); /* exact */
    const double sp = (double)(1 + f.ts1) / n;
    assert_true(sp >= sp_low(bitrate) - 1e-12 && sp <= 0.90 + 1e-12);
    int exact;
    const double best = best_error(pclk, bitrate, &exact);
    const double e = sp > 0.875 ? sp - 0.875 : 0.875 - sp;
    assert_true(best >= 0 && e <= best + 1e-12);
    assert_true(f.sjw <= f.ts2 && f.sjw <= f.ts1 && f.sjw <= 4);
    assert_int_equal(btr >> 26, 0); /* no loop-back, no silent mode, nothing reserved */
}

static const uint32_t clocks[] = {42000000u, 16000000u};
static const uint32_t rates[] = {125000u, 250000u, 500000u, 1000000u};

static void board_clocks_all_rates(void **state)
{
    (void)state;
    for (size_t c = 0; c < sizeof clocks / sizeof *clocks; ++c)
        for (size_t r = 0; r < sizeof rates / sizeof *rates; ++r) {
            uint32_t btr = 0;
            assert_int_equal(bxcan_timing_compute(clocks[c], rates[r], &btr), BXCAN_TIMING_OK);
            check_btr(clocks[c], rates[r], btr);
        }
}

/* Worked by hand.  42 MHz / 500k = 84 clocks per bit: 12, 14 or 21 quanta.  21 would need
 * TS1 = 17 (> 16) near 87.5 %; 12 gives 83.3 or 91.7 %; 14 gives 12/14 = 85.7 %: prescaler 6,
 * TS1 11, TS2 2, SJW 2 -> fields 5, 10, 1, 1. */
static void worked_values(void **state)
{
    (void)state;
    static const struct {
        uint32_t pclk, rate, btr;
    } w[] = {
        {42000000u, 500000u, 5u | 10u << 16 | 1u << 20 | 1u << 24},
        /* 42 clocks: 14 quanta (12/14 = 85.7 %; 21 quanta reach only 17/21 = 81 %) */
        {42000000u, 1000000u, 2u | 10u << 16 | 1u << 20 | 1u << 24},
        /* 168 clocks: 8 quanta give 7/8 = 87.5 % exactly (24 would need TS1 = 20) */
        {42000000u, 250000u, 20u | 5u << 16 | 0u << 20 | 0u << 24},
        /* 336 clocks: 16 quanta, 14/16 = 87.5 %, prescaler 21 */
        {42000000u, 125000u, 20u | 12u << 16 | 1u << 20 | 1u << 24},
        /* 16 clocks: 8 and 16 quanta both exact at 87.5 %: the finer one, prescaler 1 */
        {16000000u, 1000000u, 0u | 12u << 16 | 1u << 20 | 1u << 24},
        {16000000u, 500000u, 1u | 12u << 16 | 1u << 20 | 1u << 24},
    };
    for (size_t i = 0; i < sizeof w / sizeof *w; ++i) {
        uint32_t btr = 0;
        assert_int_equal(bxcan_timing_compute(w[i].pclk, w[i].rate, &btr), BXCAN_TIMING_OK);
        assert_int_equal(btr, w[i].btr);
    }
}

/* Over many clocks and rates: success exactly when the brute force finds an exact configuration
 * in range, and then a valid one; the error kind matches what the brute force saw. */
static void agrees_with_brute_force(void **state)
{
    (void)state;
    static const uint32_t mhz[] = {8, 10, 12, 13, 16, 20, 24, 25, 30, 32, 36, 40, 42, 48};
    static const uint32_t rate[] = {10000,  20000,  33333,  50000,  83333,  100000, 125000,
                                    250000, 300001, 500000, 800000, 1000000};
    for (size_t c = 0; c < sizeof mhz / sizeof *mhz; ++c)
        for (size_t r = 0; r < sizeof rate / sizeof *rate; ++r) {
            const uint32_t pclk = mhz[c] * 1000000u;
            int exact;
            const double best = best_error(pclk, rate[r], &exact);
            uint32_t btr = 0;
            const bxcan_timing_status s = bxcan_timing_compute(pclk, rate[r], &btr);
            if (best >= 0) {
                assert_int_equal(s, BXCAN_TIMING_OK);
                check_btr(pclk, rate[r], btr);
            } else {
                assert_int_equal(s, exact ? BXCAN_TIMING_SAMPLE_POINT : BXCAN_TIMING_INEXACT);
            }
        }
}

static void impossible_requests(void **state)
{
    (void)state;
    uint32_t btr = 0xA5A5A5A5u;
    /* 1M from 6 MHz: 6 quanta per bit at most, fewer than 8. */
    assert_int_equal(bxcan_timing_compute(6000000u, 1000000u, &btr), BXCAN_TIMING_INEXACT);
    /* A rate that does not divide the clock. */
    assert_int_equal(bxcan_timing_compute(42000000u, 300001u, &btr), BXCAN_TIMING_INEXACT);
    /* 800k from 42 MHz: 52.5 clocks per bit. */
    assert_int_equal(bxcan_timing_compute(42000000u, 800000u, &btr), BXCAN_TIMING_INEXACT);
    /* 1 kbit/s from 42 MHz: 42000 clocks need a prescaler > 1024 even at 25 quanta. */
    assert_int_equal(bxcan_timing_compute(42000000u, 1000u, &btr), BXCAN_TIMING_INEXACT);
    /* 500k from 6.5 MHz: 13 clocks, only 13 quanta: 11/13 = 84.6 % or 12/13 = 92.3 %. */
    assert_int_equal(bxcan_timing_compute(6500000u, 500000u, &btr), BXCAN_TIMING_SAMPLE_POINT);
    assert_int_equal(bxcan_timing_compute(0u, 500000u, &btr), BXCAN_TIMING_BAD_ARG);
    assert_int_equal(bxcan_timing_compute(42000000u, 0u, &btr), BXCAN_TIMING_BAD_ARG);
    assert_int_equal(btr, 0xA5A5A5A5u); /* untouched on every error */
    /* The same 13 quanta at 1M (6.5 -> 13 MHz) are fine: 75..90 % allows 11/13. */
    assert_int_equal(bxcan_timing_compute(13000000u, 1000000u, &btr), BXCAN_TIMING_OK);
    check_btr(13000000u, 1000000u, btr);
}

static void decode_for_diagnostics(void **state)
{
    (void)state;
    /* prescaler 6, TS1 11, TS2 2, SJW 2 at 42 MHz: 14 quanta, 500 kbit/s, 12/14 = 85.71 %. */
    const uint32_t btr = 5u | 10u << 16 | 1u << 20 | 1u << 24;
    bxcan_btr_info i = bxcan_btr_decode(btr, 42000000u);
    assert_int_equal(i.prescaler, 6);
    assert_int_equal(i.ts1, 11);
    assert_int_equal(i.ts2, 2);
    assert_int_equal(i.sjw, 2);
    assert_int_equal(i.quanta, 14);
    assert_int_equal(i.bitrate_hz, 500000);
    assert_true(i.bitrate_exact);
    assert_int_equal(i.sample_point_bp, 8571);
    /* The same register at 16 MHz: 16e6 / 84 = 190476.19 bit/s, not exact. */
    i = bxcan_btr_decode(btr, 16000000u);
    assert_int_equal(i.bitrate_hz, 190476);
    assert_false(i.bitrate_exact);
    /* Every field at its maximum: prescaler 1024, TS1 16, TS2 8, SJW 4; 25 quanta, 17/25. */
    i = bxcan_btr_decode(0x3FFu | 0xFu << 16 | 0x7u << 20 | 0x3u << 24, 25600000u);
    assert_int_equal(i.prescaler, 1024);
    assert_int_equal(i.quanta, 25);
    assert_int_equal(i.sjw, 4);
    assert_int_equal(i.bitrate_hz, 1000);
    assert_true(i.bitrate_exact);
    assert_int_equal(i.sample_point_bp, 6800);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(board_clocks_all_rates), cmocka_unit_test(worked_values),
        cmocka_unit_test(agrees_with_brute_force), cmocka_unit_test(impossible_requests),
        cmocka_unit_test(decode_for_diagnostics),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
