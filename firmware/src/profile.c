#include "fw/profile.h"

static tse_real ramp_time(tse_real V, tse_real a_max, tse_real j_max)
{
    const tse_real by_acc = TSE_R(2.0) * V / a_max;
    const tse_real by_jerk = tse_sqrt(TSE_R(2.0) * TSE_PI * V / j_max);
    return by_acc > by_jerk ? by_acc : by_jerk;
}

/* The profile with cruise speed V (if D allows a cruise at V; else the largest V that does). */
static void shape(fw_profile *p, tse_real V, tse_real a_max, tse_real j_max)
{
    tse_real Ta = ramp_time(V, a_max, j_max);
    if (V * Ta > p->D) {
        /* No room to cruise: the speed at which the two ramps meet, for whichever limit binds.
         * V Ta(V) = D with Ta = 2V/A gives V = sqrt(A D / 2); with Ta = sqrt(2 pi V/J),
         * V = cbrt(D^2 J / (2 pi)).  The smaller one satisfies both. */
        const tse_real v_acc = tse_sqrt(a_max * p->D / TSE_R(2.0));
        const tse_real v_jerk = tse_cbrt(p->D * p->D * j_max / (TSE_R(2.0) * TSE_PI));
        V = v_acc < v_jerk ? v_acc : v_jerk;
        Ta = p->D / V; /* the ramps meet exactly, whatever rounding ramp_time would leave */
    }
    p->V = V;
    p->Ta = Ta;
    p->Tc = p->D / V - Ta;
    if (p->Tc < TSE_R(0.0))
        p->Tc = TSE_R(0.0);
    p->T = TSE_R(2.0) * Ta + p->Tc;
}

int fw_profile_plan(fw_profile *p, tse_real D, tse_real v_max, tse_real a_max, tse_real j_max,
                    tse_real min_duration)
{
    if (!(D >= TSE_R(0.0)) || !isfinite(D) || !(v_max > TSE_R(0.0)) || !(a_max > TSE_R(0.0)) ||
        !(j_max > TSE_R(0.0)) || !isfinite(v_max) || !isfinite(a_max) || !isfinite(j_max) ||
        !(min_duration >= TSE_R(0.0)) || !isfinite(min_duration))
        return -1;
    p->D = D;
    if (D == TSE_R(0.0)) {
        p->V = p->Ta = TSE_R(0.0);
        p->Tc = p->T = min_duration;
        return 0;
    }
    shape(p, v_max, a_max, j_max);
    if (p->T >= min_duration)
        return 0;
    /* Too fast for the requested duration: lower the cruise speed.  The duration falls
     * monotonically with V (dT/dV = (V Ta - D)/V^2 <= 0 on an accel-bound ramp, and
     * (V Ta/2 - D)/V^2 < 0 on a jerk-bound one), so bisection finds it. */
    tse_real lo = TSE_R(0.0), hi = p->V;
    for (int it = 0; it < 100 && hi - lo > TSE_REAL_EPS * hi; ++it) {
        const tse_real mid = TSE_R(0.5) * (lo + hi);
        shape(p, mid, a_max, j_max);
        if (p->T > min_duration)
            lo = mid;
        else
            hi = mid;
    }
    shape(p, hi, a_max, j_max);
    /* Bisection leaves T a hair short of the request: the cruise takes up the rest. */
    if (p->T < min_duration) {
        const tse_real k = min_duration / p->T;
        fw_profile_stretch(p, k);
    }
    return 0;
}

void fw_profile_stretch(fw_profile *p, tse_real k)
{
    if (!(k > TSE_R(1.0)))
        return;
    p->V /= k;
    p->Ta *= k;
    p->Tc *= k;
    p->T = TSE_R(2.0) * p->Ta + p->Tc;
}

/* The ramp from rest to V over Ta, at time t in [0, Ta]. */
static void ramp(tse_real V, tse_real Ta, tse_real t, tse_real *x, tse_real *v, tse_real *a)
{
    const tse_real w = TSE_R(2.0) * TSE_PI / Ta;
    const tse_real s = tse_sin(w * t), c = tse_cos(w * t);
    *x = V * (t * t / (TSE_R(2.0) * Ta) + (c - TSE_R(1.0)) / (w * w * Ta));
    *v = V * (t / Ta - s / (w * Ta));
    *a = V / Ta * (TSE_R(1.0) - c);
}

void fw_profile_eval(const fw_profile *p, tse_real t, tse_real *x, tse_real *v, tse_real *a)
{
    if (p->D == TSE_R(0.0) || !(t > TSE_R(0.0))) {
        *x = TSE_R(0.0);
        *v = TSE_R(0.0);
        *a = TSE_R(0.0);
        return;
    }
    if (t >= p->T) {
        *x = p->D;
        *v = TSE_R(0.0);
        *a = TSE_R(0.0);
        return;
    }
    if (t < p->Ta) {
        ramp(p->V, p->Ta, t, x, v, a);
    } else if (t <= p->Ta + p->Tc) {
        *x = p->V * (TSE_R(0.5) * p->Ta + (t - p->Ta));
        *v = p->V;
        *a = TSE_R(0.0);
    } else {
        /* The ramp down mirrors the ramp up in time and position. */
        ramp(p->V, p->Ta, p->T - t, x, v, a);
        *x = p->D - *x;
        *a = -*a;
    }
}

void fw_profile_range(const fw_profile *p, tse_real t0, tse_real t1, tse_real v[2], tse_real a[2])
{
    if (t0 < TSE_R(0.0))
        t0 = TSE_R(0.0);
    if (t1 > p->T)
        t1 = p->T;
    if (t1 < t0)
        t1 = t0;
    const tse_real at[6] = {t0, t1, TSE_R(0.5) * p->Ta, p->Ta, p->Ta + p->Tc, p->T - TSE_R(0.5) * p->Ta};
    for (int i = 0; i < 6; ++i) {
        if (i >= 2 && !(at[i] > t0 && at[i] < t1))
            continue;
        tse_real x, vi, ai;
        fw_profile_eval(p, at[i], &x, &vi, &ai);
        if (i == 0 || vi < v[0])
            v[0] = vi;
        if (i == 0 || vi > v[1])
            v[1] = vi;
        if (i == 0 || ai < a[0])
            a[0] = ai;
        if (i == 0 || ai > a[1])
            a[1] = ai;
    }
    /* The formulas' rounding: a few units in the last place of the profile's own scales. */
    const tse_real dv = TSE_R(16.0) * TSE_REAL_EPS * p->V;
    const tse_real da = p->Ta > TSE_R(0.0) ? TSE_R(16.0) * TSE_REAL_EPS * p->V / p->Ta : TSE_R(0.0);
    v[0] -= dv;
    v[1] += dv;
    a[0] -= da;
    a[1] += da;
}
