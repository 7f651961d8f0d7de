#include "fx_math.h"

/* floor(sqrt(x)) of a 32-bit value: Newton's iteration y <- (y + x / y) / 2 from a power of two
 * above the root decreases to it (a 32 / 32 division a step, four or five steps). */
static uint32_t isqrt32(uint32_t x)
{
    if (x == 0)
        return 0;
    uint32_t y = (uint32_t)1 << ((33 - fx_clz32(x)) / 2);
    for (;;) {
        const uint32_t z = (y + x / y) >> 1;
        if (z >= y)
            return y;
        y = z;
    }
}

uint32_t fx_isqrt64(uint64_t x)
{
    if (x >> 32 == 0)
        return isqrt32((uint32_t)x);
    /* x 4^j with its top bits set, so that its top word's root y has 16 bits; the root of the
     * whole is y 2^16 + (xn - y^2 2^32) / (y 2^17) to within two (the first term left out of the
     * root's expansion is below 2^15 / y), then settled exactly. */
    const int s = fx_clz64(x) & ~1;
    const uint64_t xn = x << s;
    const uint32_t y = isqrt32((uint32_t)(xn >> 32));
    const uint64_t rem = xn - ((uint64_t)y * y << 32);   /* below (2 y + 1) 2^32 */
    /* y >= 2^15: xn's top word is at least 2^30 (x >= 2^32, shifted up to its top bits). */
    uint64_t r = ((uint64_t)y << 16) + (uint32_t)(rem >> 17) / y; // NOLINT(clang-analyzer-core.DivideZero)
    if (r > 0xFFFFFFFFu)
        r = 0xFFFFFFFFu;
    while (r * r > xn)
        --r;
    while (r < 0xFFFFFFFFu && (r + 1) * (r + 1) <= xn)
        ++r;
    return (uint32_t)(r >> (s / 2));
}
