#include "hal_fault/fault_rng.h"

/* splitmix64 scrambles the seed (so that seeds 1, 2, 3 start far apart, and 0 is not the
 * all-zero state xorshift cannot leave); xorshift64* draws. */
void fault_rng_seed(fault_rng *r, uint64_t seed)
{
    uint64_t z = seed + 0x9E3779B97F4A7C15ull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    r->s = z ? z : 0x2545F4914F6CDD1Dull;
}

uint64_t fault_rng_next(fault_rng *r)
{
    uint64_t x = r->s;
    x ^= x >> 12;
    x ^= x << 25;
    x ^= x >> 27;
    r->s = x;
    return x * 0x2545F4914F6CDD1Dull;
}

double fault_rng_unit(fault_rng *r)
{
    return (double)(fault_rng_next(r) >> 11) * 0x1.0p-53;
}

uint32_t fault_rng_below(fault_rng *r, uint32_t n)
{
    /* The top 32 bits scaled: a bias of at most n / 2^32, immaterial for fault draws. */
    return (uint32_t)(((fault_rng_next(r) >> 32) * (uint64_t)n) >> 32);
}
