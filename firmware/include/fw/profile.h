/* Rest-to-rest speed profile along a path of length D, with jerk-limited ramps.
 *
 * Each ramp is cycloidal: acceleration a(t) = (V/Ta)(1 - cos(2 pi t/Ta)) rises from 0 and falls
 * back to 0, so jerk is bounded (2 pi V/Ta^2) and continuous, with peak acceleration 2V/Ta.  A
 * ramp covers V Ta/2, exactly as a linear ramp would, so the profile's integral is D by
 * construction: ramp up, cruise at V for Tc, ramp down. */
#ifndef FW_PROFILE_H
#define FW_PROFILE_H

#include "tse/real.h"

typedef struct {
    tse_real D;  /* length */
    tse_real V;  /* cruise speed */
    tse_real Ta; /* duration of each ramp */
    tse_real Tc; /* duration of the cruise */
    tse_real T;  /* total: 2 Ta + Tc */
} fw_profile;

/* Fastest profile over D within v_max, a_max, j_max, then slowed down (lower cruise speed) until
 * it lasts at least min_duration.  Returns 0, or -1 for a non-positive or non-finite argument
 * (D = 0 gives the empty profile: T = min_duration, never moving). */
int fw_profile_plan(fw_profile *p, tse_real D, tse_real v_max, tse_real a_max, tse_real j_max,
                    tse_real min_duration);

/* Slows the whole profile down by k >= 1: speeds / k, accelerations / k^2, jerks / k^3. */
void fw_profile_stretch(fw_profile *p, tse_real k);

/* The range of the speed and of the acceleration over [t0, t1] (clamped to [0, T]): both are
 * monotone between the profile's breakpoints (Ta/2, Ta, Ta + Tc, T - Ta/2), so their extremes are
 * at the ends or at a breakpoint inside.  Widened by the formulas' rounding. */
void fw_profile_range(const fw_profile *p, tse_real t0, tse_real t1, tse_real v[2], tse_real a[2]);

/* Position, speed and acceleration at time t (clamped to [0, T]). */
void fw_profile_eval(const fw_profile *p, tse_real t, tse_real *x, tse_real *v, tse_real *a);

#endif
