/* BTR from clock and bit rate: try every quanta count 8..25 that divides the clock exactly, and
 * for each the TS1/TS2 split nearest 87.5 % among those inside CiA 301's range (which is not
 * symmetric about 87.5 % at 800k and above, so the range is applied before choosing); keep the
 * best.  Exact integer arithmetic throughout (no rounding can turn a wrong rate into a "right"
 * one). */
#include "hal_stm32f4/bxcan_timing.h"

#include "hal_stm32f4/regs_can.h"

enum { Q_MIN = 8, Q_MAX = 25, TS1_MAX = 16, TS2_MAX = 8, SJW_MAX = 4, BRP_MAX = 1024 };

typedef struct {
    uint32_t quanta, ts1, ts2; /* in quanta; quanta == 0: none yet */
} split;

/* Distance of the sample point (1 + ts1) / quanta from 7/8, as a fraction num / (8 x quanta). */
static uint32_t sp_error_num(split s)
{
    const int32_t d = 8 * (int32_t)(1u + s.ts1) - 7 * (int32_t)s.quanta;
    return (uint32_t)(d < 0 ? -d : d);
}

/* a strictly better than b: nearer 87.5 %, or as near with more quanta. */
static bool better(split a, split b)
{
    if (b.quanta == 0)
        return true;
    const uint32_t ea = sp_error_num(a) * b.quanta, eb = sp_error_num(b) * a.quanta;
    return ea < eb || (ea == eb && a.quanta > b.quanta);
}

/* CiA 301's valid range of the sample point for this bit rate. */
static bool sp_in_range(split s, uint32_t bitrate)
{
    const uint32_t sp = 1u + s.ts1; /* compared with quanta x percent / 100 */
    const uint32_t low_pct = bitrate >= 800000u ? 75u : 85u;
    return sp * 100u >= low_pct * s.quanta && sp * 100u <= 90u * s.quanta;
}

/* Best TS1/TS2 split of `quanta` within the field ranges and the sample-point range, or
 * quanta == 0 when none fits. */
static split best_split(uint32_t quanta, uint32_t bitrate)
{
    split best = {0, 0, 0};
    for (uint32_t ts2 = 1; ts2 <= TS2_MAX; ++ts2) {
        if (quanta < 2u + ts2 || quanta - 1u - ts2 > TS1_MAX)
            continue;
        const split s = {quanta, quanta - 1u - ts2, ts2};
        if (sp_in_range(s, bitrate) && better(s, best))
            best = s;
    }
    return best;
}

static uint32_t encode(uint32_t prescaler, split s)
{
    const uint32_t sjw = s.ts2 < SJW_MAX ? s.ts2 : SJW_MAX;
    return (prescaler - 1u) << CAN_BTR_BRP_SHIFT | (s.ts1 - 1u) << CAN_BTR_TS1_SHIFT |
           (s.ts2 - 1u) << CAN_BTR_TS2_SHIFT | (sjw - 1u) << CAN_BTR_SJW_SHIFT;
}

bxcan_timing_status bxcan_timing_compute(uint32_t pclk_hz, uint32_t bitrate, uint32_t *btr)
{
    if (pclk_hz == 0 || bitrate == 0)
        return BXCAN_TIMING_BAD_ARG;
    if (pclk_hz % bitrate != 0)
        return BXCAN_TIMING_INEXACT;
    const uint32_t clocks_per_bit = pclk_hz / bitrate;
    split best = {0, 0, 0};
    uint32_t best_prescaler = 0;
    bool exact = false;
    for (uint32_t q = Q_MIN; q <= Q_MAX; ++q) {
        if (clocks_per_bit % q != 0 || clocks_per_bit / q > BRP_MAX)
            continue;
        exact = true;
        const split s = best_split(q, bitrate);
        if (s.quanta != 0 && better(s, best)) {
            best = s;
            best_prescaler = clocks_per_bit / q;
        }
    }
    if (!exact)
        return BXCAN_TIMING_INEXACT;
    if (best.quanta == 0)
        return BXCAN_TIMING_SAMPLE_POINT;
    *btr = encode(best_prescaler, best);
    return BXCAN_TIMING_OK;
}

const char *bxcan_timing_str(bxcan_timing_status s)
{
    switch (s) {
    case BXCAN_TIMING_OK:
        return "ok";
    case BXCAN_TIMING_BAD_ARG:
        return "zero clock or bit rate";
    case BXCAN_TIMING_INEXACT:
        return "bit rate not reachable exactly from this clock";
    case BXCAN_TIMING_SAMPLE_POINT:
        return "no sample point within CiA 301's range";
    }
    return "?";
}

bxcan_btr_info bxcan_btr_decode(uint32_t btr, uint32_t pclk_hz)
{
    bxcan_btr_info i;
    i.prescaler = (btr >> CAN_BTR_BRP_SHIFT & CAN_BTR_BRP_MASK) + 1u;
    i.ts1 = (btr >> CAN_BTR_TS1_SHIFT & CAN_BTR_TS1_MASK) + 1u;
    i.ts2 = (btr >> CAN_BTR_TS2_SHIFT & CAN_BTR_TS2_MASK) + 1u;
    i.sjw = (btr >> CAN_BTR_SJW_SHIFT & CAN_BTR_SJW_MASK) + 1u;
    i.quanta = 1u + i.ts1 + i.ts2;
    const uint32_t clocks_per_bit = i.prescaler * i.quanta; /* <= 1024 x 25: no overflow */
    const uint32_t rem = pclk_hz % clocks_per_bit;
    i.bitrate_hz = pclk_hz / clocks_per_bit + (rem >= clocks_per_bit - rem ? 1u : 0u);
    i.bitrate_exact = rem == 0;
    i.sample_point_bp = ((1u + i.ts1) * 10000u + i.quanta / 2u) / i.quanta;
    return i;
}
