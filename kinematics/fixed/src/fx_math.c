#include "fx_math.h"

uint32_t fx_isqrt64(uint64_t x)
{
    /* Digit by digit (two bits of x per bit of the root), from the highest pair that is set. */
    if (x == 0)
        return 0;
    uint64_t rem = x, res = 0;
    uint64_t one = (uint64_t)1 << ((63 - fx_clz64(x)) & ~1);
    while (one != 0) {
        if (rem >= res + one) {
            rem -= res + one;
            res = (res >> 1) + one;
        } else {
            res >>= 1;
        }
        one >>= 2;
    }
    return (uint32_t)res;
}

int64_t fx_div(int64_t num, int64_t den, int sh)
{
    const int neg = (num < 0) != (den < 0);
    uint64_t a = fx_abs64(num), b = fx_abs64(den);
    if (b == 0)
        return neg ? INT64_MIN : INT64_MAX;
    if (a == 0)
        return 0;
    /* a << sh / b: shift a up as far as 62 bits allow, and b down by what remains. */
    int up = fx_clz64(a) - 2;
    if (up > sh)
        up = sh;
    a <<= up;
    const int down = sh - up;
    if (down > 0) {
        if (down >= 64 - fx_clz64(b))
            return neg ? INT64_MIN : INT64_MAX; /* b would vanish: the quotient is above 2^62 */
        b >>= down;
    }
    const uint64_t q = (a + b / 2u) / b;
    return neg ? -(int64_t)q : (int64_t)q;
}
