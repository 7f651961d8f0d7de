/* Sine and cosine of an angle in Q28 radians, in Q30, by integer arithmetic only.
 *
 * The angle becomes a fraction of a turn in 32 bits (t = angle / (2 pi) * 2^32, modulo 2^32: this
 * is the wrap, exact for any angle), the nearest quarter turn comes off its top bits, and what is
 * left, |r| <= 1/8 turn = pi/4, goes back to radians in Q31 for the Taylor series of sin and cos
 * (terms to r^13 and r^12: the first left out is below 7e-12 at pi/4), evaluated by Horner's rule
 * in r^2 with Q30 coefficients.  The error is that of the roundings: a few 2^-30, under 1e-8
 * (tests/kinematics/test_ik_fixed.c measures it against the C library's double). */
#include "fx_math.h"
#include "tse/ik_fixed.h"

/* 2^33 / (2 pi): Q28 radians times this, shifted right by 29, is 2^32 per turn. */
#define TURNS_PER_RAD_Q29 1367130551LL
/* pi in Q29: a 2^-32 turn times 2 pi, in Q31 radians, is r * pi (Q29) >> 29. */
#define PI_Q29 1686629713LL

static const int32_t SIN_C[6] = {1073741824, -178956971, 8947849, -213044, 2959, -27};
static const int32_t COS_C[7] = {1073741824, -536870912, 44739243, -1491308, 26631, -296, 2};

void tse_fx_sincos(int32_t angle, int32_t *s, int32_t *c)
{
    /* Turns modulo 1 in 32 bits: the product's low 32 bits after the shift. */
    const uint32_t t = (uint32_t)(uint64_t)fx_shr((int64_t)angle * TURNS_PER_RAD_Q29, 29);
    const uint32_t quadrant = (t + 0x20000000u) >> 30;
    const int32_t r = (int32_t)(t - (quadrant << 30)); /* [-2^29, 2^29): +-1/8 turn */
    const int32_t x = (int32_t)fx_shr((int64_t)r * PI_Q29, 29); /* Q31 radians, |x| <= pi/4 */
    const int32_t z = (int32_t)fx_shr((int64_t)x * x, 31);      /* x^2, Q31 */
    int32_t ps = SIN_C[5], pc = COS_C[6];
    for (int k = 4; k >= 0; --k)
        ps = SIN_C[k] + (int32_t)fx_shr((int64_t)ps * z, 31);
    for (int k = 5; k >= 0; --k)
        pc = COS_C[k] + (int32_t)fx_shr((int64_t)pc * z, 31);
    const int32_t sr = (int32_t)fx_shr((int64_t)x * ps, 31); /* Q30 */
    const int32_t cr = pc;
    /* A quarter turn swaps and negates the pair. */
    const int32_t s0 = (quadrant & 1u) ? cr : sr;
    const int32_t c0 = (quadrant & 1u) ? sr : cr;
    *s = (quadrant & 2u) ? -s0 : s0;
    *c = ((quadrant + 1u) & 2u) ? -c0 : c0;
}

uint32_t tse_fx_isqrt(uint64_t x)
{
    return fx_isqrt64(x);
}
