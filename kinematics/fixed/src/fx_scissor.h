/* One scissor's solution in fixed point (kinematics.md, "The solution and what makes it valid"):
 * bounded Newton on (F1, F2) from a seed, and when it stalls, leaves the physical sheet or ends
 * outside the limits, every real root of the quartic in m = a + b, each polished by Newton on
 * (F1, F2).  Internal to the fixed build; what it promises is what fx_scissor_solve says. */
#ifndef TSE_FX_SCISSOR_H
#define TSE_FX_SCISSOR_H

#include <stdint.h>

#include "tse/ik_fixed.h"

/* What the constraints of one scissor need of its ball joint. */
typedef struct {
    int32_t d[3];  /* C - O_i, Q24 (valid when !far) */
    int32_t u, v;  /* d . a_i, d . b_i, Q24 (M, the quartic) */
    int32_t u26, v26; /* the same in Q26 (F) */
    int64_t rho2;  /* |d|^2, Q50 */
    int far;       /* beyond any reach (or the format's room): no physical solution */
} fx_local;

typedef struct {
    int32_t s_a, s_b; /* Q24 */
    int64_t det;      /* det M / 4, Q48 (> 0 on the physical sheet) */
    int32_t mu;       /* Q30 */
    int64_t n_min;    /* the smaller squared norm of M's rows, over 4, Q48 */
    int64_t w2;       /* base width squared, Q48 */
    int32_t ea, eb;   /* M's first row, halved (for the type-2 check), Q24 */
    int iterations;
    int fallback;     /* 1 when the quartic was needed */
} fx_sol;

/* The ball joint C (Q28, in 64 bits) of scissor i in its frame. */
void fx_localize(const tse_fx_geometry *g, int i, const int64_t C[3], fx_local *loc);

/* Whether the solution is inside the stroke and the stops. */
int fx_within_limits(const tse_fx_geometry *g, const fx_sol *s);

/* The type-1 check, with room for the slides' rounding (mu_guard). */
int fx_mu_clear(const tse_fx_geometry *g, const fx_sol *s);

/* The solution on the physical branch nearest the seed, as tse_scissor_solve: TSE_OK with out
 * filled (limits not yet checked when out->fallback), or TSE_UNREACHABLE. */
tse_status fx_scissor_solve(const tse_fx_geometry *g, const fx_local *loc, int32_t seed_a, int32_t seed_b,
                            fx_sol *out);

#endif
