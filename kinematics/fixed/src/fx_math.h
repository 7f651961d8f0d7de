/* Integer arithmetic of the fixed-point kinematics (docs/kinematics.md, "The fixed-point build"):
 * products through 64-bit intermediates, shifts that are never undefined, a square root and
 * quotients, all in integers (a Cortex-M3 has a 32 x 32 -> 64 multiply, a 32 / 32 divide and a
 * count of leading zeros; nothing here needs more).
 *
 * Every shift by a count computed at run time goes through fx_shr / fx_shl, which take any count:
 * a count of 64 or more gives 0 (or -1 for a negative value shifted right), never the undefined
 * behaviour of C's operators (an earlier attempt shifted by 66 in a scaling helper).  Shifts by a
 * constant are written with C's operators where the value is known to fit; a left shift of a
 * value that may be negative goes through fx_shl (undefined in C otherwise). */
#ifndef TSE_FX_MATH_H
#define TSE_FX_MATH_H

#include <stdint.h>

/* C11 leaves the right shift of a negative value to the implementation; GCC and Clang (the
 * project's compilers, on the host and the board) document it as arithmetic, which this checks. */
/* cppcheck-suppress shiftNegativeLHS ; the point: this asserts how the compiler shifts one */
_Static_assert((-5 >> 1) == -3, "the right shift of a negative value must be arithmetic");

/* x >> n, rounded toward minus infinity, for any n (n < 0 shifts left through fx_shl). */
static inline int64_t fx_shr(int64_t x, int n)
{
    if (n <= 0)
        return n == 0 ? x : (int64_t)((uint64_t)x << (-n > 63 ? 63 : -n));
    if (n > 63)
        return x < 0 ? -1 : 0;
    /* cppcheck-suppress shiftNegativeLHS ; arithmetic, as the _Static_assert above checks */
    /* cppcheck-suppress shiftTooManyBitsSigned ; the same */
    return x >> n;
}

/* x << n for 0 <= n <= 63, through unsigned arithmetic (a negative x is not undefined); the
 * caller knows the result fits. */
static inline int64_t fx_shl(int64_t x, int n)
{
    if (n <= 0)
        return fx_shr(x, -n);
    if (n > 63)
        return 0;
    return (int64_t)((uint64_t)x << n);
}

/* Leading zeros of a 32- and a 64-bit value (32 and 64 for zero). */
static inline int fx_clz32(uint32_t x)
{
    return x ? __builtin_clz(x) : 32;
}

static inline int fx_clz64(uint64_t x)
{
    return (x >> 32) ? fx_clz32((uint32_t)(x >> 32)) : 32 + fx_clz32((uint32_t)x);
}

static inline uint64_t fx_abs64(int64_t x)
{
    return x < 0 ? (uint64_t)0 - (uint64_t)x : (uint64_t)x;
}

/* Bits needed for |x| (0 for 0), but for a negative power of two, one less (the bits of
 * -x - 1, which costs no negation): every caller leaves a bit of room for it. */
static inline int fx_bits64(int64_t x)
{
    /* cppcheck-suppress shiftTooManyBitsSigned ; arithmetic (the _Static_assert above): x's sign */
    return 64 - fx_clz64((uint64_t)(x ^ (x >> 63)));
}

/* (a * b) >> sh for 0 <= sh <= 32, rounded toward minus infinity, without a 96-bit product: the
 * high word's part is exact, the low word's is a 32 x 32 -> 64 product.  The caller knows the
 * result fits in 64 bits. */
static inline int64_t fx_mul64x32(int64_t a, int32_t b, int sh)
{
    const int64_t hi = (int64_t)(int32_t)(uint32_t)((uint64_t)a >> 32) * b; /* a's signed top word */
    const int64_t lo = (int64_t)(uint64_t)(uint32_t)a * b;                   /* unsigned low word */
    return fx_shl(hi, 32 - sh) + fx_shr(lo, sh);
}

/* (a * b) >> sh of two 32-bit values, 0 <= sh <= 63. */
static inline int64_t fx_mul32(int32_t a, int32_t b, int sh)
{
    return fx_shr((int64_t)a * b, sh);
}

/* Rounded to nearest: (a * b + 2^(sh-1)) >> sh, 1 <= sh <= 62. */
static inline int32_t fx_mul32r(int32_t a, int32_t b, int sh)
{
    return (int32_t)fx_shr((int64_t)a * b + ((int64_t)1 << (sh - 1)), sh);
}

/* floor(sqrt(x)) of a 64-bit value (fx_math.c). */
uint32_t fx_isqrt64(uint64_t x);

/* The reciprocal of a 64-bit divisor, to 29 significant bits or better: 1 / |den| =
 * r 2^-(94 - k), r in (2^30, 2^31] (a 32 / 32 division and one Newton-Raphson step; the Cortex-M3
 * has no 64-bit divide, and the C library's takes a hundred instructions and more). */
typedef struct {
    uint32_t r;
    int k;   /* leading zeros of |den| */
    int neg; /* den < 0 */
} fx_recip;

static inline fx_recip fx_recip_of(int64_t den)
{
    const uint64_t d = fx_abs64(den);
    const int k = fx_clz64(d);
    const uint32_t dn = (uint32_t)((d << (k & 63)) >> 32); /* [2^31, 2^32) */
    const uint32_t q = 0xFFFFFFFFu / ((dn >> 16) + 1u);    /* ~2^48 / dn, from below */
    const uint32_t r0 = q << 14;                            /* ~2^62 / dn */
    const uint64_t e = ((uint64_t)1 << 62) - (uint64_t)dn * r0;
    const uint32_t r1 = r0 + (uint32_t)(((uint64_t)r0 * (uint32_t)(e >> 31)) >> 31);
    return (fx_recip){r1, k, den < 0};
}

/* num 2^sh / den (den's reciprocal rc) for |num| < 2^61, rounded to nearest: to 29 significant
 * bits, and to within one unit of the result whatever its size (the product is taken whole, so a
 * small numerator loses nothing); saturated to +-2^62 when the quotient could come near that (a
 * Newton step that large is clipped anyway). */
static inline int64_t fx_mul_recip(int64_t num, fx_recip rc, int sh)
{
    if (num == 0)
        return 0;
    const int t = 94 - rc.k - sh; /* the quotient is (num r) >> t */
    const int64_t sat = (num > 0) != rc.neg ? ((int64_t)1 << 62) : -((int64_t)1 << 62);
    if (rc.k == 64 || t < 0)
        return sat;
    int64_t hi = fx_mul64x32(num, (int32_t)(rc.r >> 1), 31); /* num r / 2^32, below 2^60 */
    if (t < 32 && fx_bits64(hi) + (32 - t) > 61)
        return sat;
    if (t >= 33 && t <= 94)
        hi += (int64_t)1 << (t - 33);
    const int64_t q = fx_shr(hi, t - 32);
    return rc.neg ? -q : q;
}

/* round(num * 2^sh / den) to 29 significant bits, den != 0 (saturated as fx_mul_recip; +-2^62
 * for den = 0). */
static inline int64_t fx_div(int64_t num, int64_t den, int sh)
{
    return fx_mul_recip(num, fx_recip_of(den), sh);
}

/* A product of many factors of known sign but widely varying size (the type-2 check's sixth
 * powers of metres): m 2^e with |m| < 2^31 after every operation.  Integers only. */
typedef struct {
    int64_t m;
    int e;
} fx_scaled;

static inline fx_scaled fx_scaled_of(int64_t v, int frac_bits)
{
    const int b = fx_bits64(v), k = b > 31 ? b - 31 : 0;
    return (fx_scaled){fx_shr(v, k), k - frac_bits};
}

static inline fx_scaled fx_scaled_mul(fx_scaled x, fx_scaled y)
{
    return fx_scaled_of(x.m * y.m, -(x.e + y.e));
}

/* x - y, aligned to the larger exponent. */
static inline fx_scaled fx_scaled_sub(fx_scaled x, fx_scaled y)
{
    const int e = x.e > y.e ? x.e : y.e;
    return fx_scaled_of(fx_shr(x.m, e - x.e) - fx_shr(y.m, e - y.e), -e);
}

/* sqrt(x) for x.m >= 0. */
static inline fx_scaled fx_scaled_sqrt(fx_scaled x)
{
    if (x.m <= 0)
        return (fx_scaled){0, 0};
    /* m up to 62 bits with an even exponent left: 31 bits of root. */
    int k = 62 - fx_bits64(x.m);
    if ((x.e - k) & 1)
        --k;
    return fx_scaled_of(fx_isqrt64((uint64_t)fx_shl(x.m, k)), -((x.e - k) / 2));
}

/* x / y in Q(frac_bits), saturated to 32 bits; y.m > 0. */
static inline int32_t fx_scaled_div(fx_scaled x, fx_scaled y, int frac_bits)
{
    const int64_t q = fx_div(x.m, y.m, 30); /* Q30 of the mantissas' ratio */
    const int64_t r = fx_shl(q, x.e - y.e + frac_bits - 30);
    const int sh = x.e - y.e + frac_bits - 30;
    if (sh > 0 && fx_bits64(q) + sh > 62)
        return q > 0 ? INT32_MAX : -INT32_MAX;
    return r > INT32_MAX ? INT32_MAX : r < -INT32_MAX ? -INT32_MAX : (int32_t)r;
}

#endif
