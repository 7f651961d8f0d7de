/* The fault layer's random numbers: seeded, so that a run with faults can be repeated exactly. */
#ifndef HAL_FAULT_RNG_H
#define HAL_FAULT_RNG_H

#include <stdint.h>

typedef struct {
    uint64_t s;
} fault_rng;

/* Any seed, 0 included, gives a usable sequence; equal seeds give equal sequences. */
void fault_rng_seed(fault_rng *r, uint64_t seed);
uint64_t fault_rng_next(fault_rng *r);
/* Uniform in [0, 1). */
double fault_rng_unit(fault_rng *r);
/* Uniform in 0 .. n - 1 (n > 0). */
uint32_t fault_rng_below(fault_rng *r, uint32_t n);

#endif
