/* Sine and cosine of one angle together, inline: the three pairs of every pose cost the inverse
 * kinematics less than one call each to the C library's sin and cos, which handle every argument
 * to the last bit and dispatch at run time.
 *
 * Arguments up to TRIG_REDUCE_MAX are reduced to r = x - k pi/2, |r| <= pi/4, by Cody-Waite with
 * pi/2 split in three: k times each of the first two parts is exact for any k the range allows.  Then
 * sin r = r + r^3 P(r^2) and cos r = 1 - r^2/2 + r^4 Q(r^2), P and Q minimax fits of relative
 * error 1.1e-17 and 1.1e-18 in double, 7.9e-9 and 1.7e-10 in float (tests/kinematics/
 * trig_coefficients.py derives them), well below the rounding of the evaluation: about one ulp in
 * all (within 1.06 up to pi/4, 2.4 beyond).  Beyond the range, and for infinities and NaN, the C library answers.  test_trig checks
 * both against long double. */
#ifndef TSE_TRIG_H
#define TSE_TRIG_H

#include "tse/real.h"

#if defined(TSE_REAL_FLOAT) && TSE_REAL_FLOAT
/* pi/2 in 13 + 13 + 24 bits: k times a 13-bit part is exact for |k| < 2^11. */
#define TRIG_PIO2_1 0x1.922p+0f
#define TRIG_PIO2_2 (-0x1.2afp-18f)
#define TRIG_PIO2_3 0x1.0b4612p-34f
#define TRIG_REDUCE_MAX 3.0e3f
/* Adding 1.5 * 2^23 rounds a float below 2^22 in magnitude to an integer. */
#define TRIG_SHIFTER 0x1.8p+23f
#else
/* pi/2 in 33 + 33 + 53 bits: k times a 33-bit part is exact for |k| < 2^20. */
#define TRIG_PIO2_1 0x1.921fb544p+0
#define TRIG_PIO2_2 0x1.0b4611a6p-34
#define TRIG_PIO2_3 0x1.3198a2e037073p-69
#define TRIG_REDUCE_MAX 1.6e6
#define TRIG_SHIFTER 0x1.8p+52
#endif
#define TRIG_PIO4 TSE_R(0.78539816339744830962)
#define TRIG_2_OVER_PI TSE_R(0.63661977236758134308)

/* sin r and cos r for |r| <= pi/4 (a little beyond costs a little accuracy, nothing else). */
static inline void tse_sincos_kernel(tse_real r, tse_real *s, tse_real *c)
{
    const tse_real z = r * r;
#if defined(TSE_REAL_FLOAT) && TSE_REAL_FLOAT
    const tse_real ps = TSE_R(-0x1.555546p-3) + z * (TSE_R(0x1.11073cp-7) + z * TSE_R(-0x1.9943e2p-13));
    const tse_real pc = TSE_R(0x1.55554ap-5) + z * (TSE_R(-0x1.6c0c34p-10) + z * TSE_R(0x1.99eb9cp-16));
#else
    const tse_real ps =
        -0x1.5555555555548p-3 +
        z * (0x1.111111110f7d0p-7 +
             z * (-0x1.a01a019bfdf4ap-13 +
                  z * (0x1.71de3567d7f9ep-19 + z * (-0x1.ae5e5a9502e40p-26 + z * 0x1.5d8fd2a391c1fp-33))));
    const tse_real pc =
        0x1.555555555554bp-5 +
        z * (-0x1.6c16c16c14f91p-10 +
             z * (0x1.a01a019c844f3p-16 +
                  z * (-0x1.27e4f7eac4b10p-22 + z * (0x1.1ee9d7b4e3fc9p-29 + z * -0x1.8fa49a0b2cb36p-37))));
#endif
    *s = r + (r * z) * ps;
    /* 1 - (z/2 - z^2 Q): the inner difference, below 0.31, rounds by at most a quarter of cos's
     * ulp (cos >= 0.7 here), z's own rounding adds under a third and the last subtraction half:
     * 1.06 ulp at worst, 0.99 seen in 2e7 arguments. */
    *c = TSE_R(1.0) - (TSE_R(0.5) * z - (z * z) * pc);
}

static inline void tse_sincos(tse_real x, tse_real *s, tse_real *c)
{
    const tse_real ax = tse_fabs(x);
    if (ax <= TRIG_PIO4) {
        tse_sincos_kernel(x, s, c);
        return;
    }
    /* Also NaN, which fails every comparison. */
    if (!(ax <= TRIG_REDUCE_MAX)) {
        *s = tse_sin(x);
        *c = tse_cos(x);
        return;
    }
    /* k, the nearest integer to x / (pi/2).  x - k TRIG_PIO2_1 is exact (both terms are, and
     * they are within a factor of two), and so is the next subtraction where r is small: r keeps
     * its relative accuracy even next to a multiple of pi/2. */
    const tse_real k = (x * TRIG_2_OVER_PI + TRIG_SHIFTER) - TRIG_SHIFTER;
    const tse_real r = ((x - k * TRIG_PIO2_1) - k * TRIG_PIO2_2) - k * TRIG_PIO2_3;
    tse_real sr, cr;
    tse_sincos_kernel(r, &sr, &cr);
    /* x = r + q pi/2: quarter turns swap and negate the pair. */
    const unsigned q = (unsigned)(int)k; /* modulo 2^N: the low bits of a negative k are right too */
    const tse_real s0 = (q & 1u) ? cr : sr;
    const tse_real c0 = (q & 1u) ? sr : cr;
    *s = (q & 2u) ? -s0 : s0;
    *c = ((q + 1u) & 2u) ? -c0 : c0;
}

#endif
