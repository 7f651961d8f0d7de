/* Speed profile: its integral is the distance, it respects every limit, and it lasts as long as
 * asked; checked by numerical integration and differentiation of what it reports. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>

#include "fw/profile.h"

static double U(double a, double b) { return a + (b - a) * rand() / (double)RAND_MAX; }

static void check_profile(const fw_profile *p, double D, double vmax, double amax, double jmax)
{
    const int n = 20000;
    const double h = p->T / n;
    double x, v, a, integral = 0.0, peak_j = 0.0, v_prev = 0.0, a_prev = 0.0, x_prev = 0.0;
    for (int i = 0; i <= n; ++i) {
        fw_profile_eval(p, i * h, &x, &v, &a);
        assert_true(v >= -1e-12 && v <= vmax * (1 + 1e-9));
        assert_true(fabs(a) <= amax * (1 + 1e-9));
        if (i > 0) {
            integral += 0.5 * (v + v_prev) * h; /* trapezoid of the reported speed */
            /* x' = v: the trapezoid rule's local error is at most h^3 |v''| / 12 <= h^3 jmax / 12 */
            assert_true(fabs((x - x_prev) - 0.5 * (v + v_prev) * h) <= h * h * h * jmax / 12 + 1e-12 * D);
            const double j = fabs(a - a_prev) / h;
            if (j > peak_j)
                peak_j = j;
        }
        v_prev = v;
        a_prev = a;
        x_prev = x;
    }
    assert_true(fabs(x - D) <= 1e-12 * D);
    assert_true(fabs(integral - D) <= 1e-6 * D);
    assert_true(peak_j <= jmax * (1 + 1e-3));
    assert_true(fabs(v) <= 1e-12 && fabs(a) <= 1e-12); /* at rest at the end */
}

static void test_random_profiles(void **state)
{
    (void)state;
    srand(3);
    for (int rep = 0; rep < 300; ++rep) {
        const double D = U(1e-4, 2.0), vmax = U(0.01, 1.0), amax = U(0.05, 5.0), jmax = U(0.5, 100.0);
        fw_profile p;
        assert_int_equal(fw_profile_plan(&p, D, vmax, amax, jmax, 0.0), 0);
        check_profile(&p, D, vmax, amax, jmax);
        /* Fastest: some limit is reached (cruise speed, peak acceleration 2V/Ta, or jerk). */
        const double peak_a = 2.0 * p.V / p.Ta, peak_j = 2.0 * TSE_PI * p.V / (p.Ta * p.Ta);
        assert_true(fabs(p.V - vmax) <= 1e-9 * vmax || fabs(peak_a - amax) <= 1e-9 * amax ||
                    fabs(peak_j - jmax) <= 1e-9 * jmax);

        /* A longer duration than the fastest is met exactly, still within the limits. */
        const double want = p.T * U(1.0, 4.0);
        assert_int_equal(fw_profile_plan(&p, D, vmax, amax, jmax, want), 0);
        assert_true(fabs(p.T - want) <= 1e-9 * want);
        check_profile(&p, D, vmax, amax, jmax);

        /* Stretching scales time and keeps the distance. */
        const double T0 = p.T, k = U(1.0, 3.0);
        fw_profile_stretch(&p, k);
        assert_true(fabs(p.T - k * T0) <= 1e-12 * p.T);
        check_profile(&p, D, vmax, amax, jmax);
    }
}

/* Speed and acceleration by the header's formulas, independently of profile.c: cycloidal ramps
 * a = (V/Ta)(1 - cos(2 pi t/Ta)), v = (V/Ta)(t - (Ta/2pi) sin(2 pi t/Ta)), mirrored at the end. */
static void by_hand(const fw_profile *p, double t, double *v, double *a)
{
    const double w = 2.0 * TSE_PI / p->Ta;
    double tr = t, sign = 1.0;
    if (t <= 0.0 || t >= p->T) {
        *v = *a = 0.0;
        return;
    }
    if (t > p->Ta && t < p->Ta + p->Tc) {
        *v = p->V;
        *a = 0.0;
        return;
    }
    if (t >= p->Ta + p->Tc) {
        tr = p->T - t;
        sign = -1.0;
    }
    *v = p->V / p->Ta * (tr - sin(w * tr) / w);
    *a = sign * p->V / p->Ta * (1.0 - cos(w * tr));
}

/* fw_profile_range holds every speed and acceleration of the span, and is no wider than the
 * values met there (sampled densely; the sampling's own gap bounded by the jerk). */
static void test_range(void **state)
{
    (void)state;
    srand(5);
    for (int rep = 0; rep < 400; ++rep) {
        fw_profile p;
        assert_int_equal(fw_profile_plan(&p, U(1e-3, 1.0), U(0.05, 1.0), U(0.1, 5.0), U(1.0, 100.0),
                                         rep % 2 ? U(0.0, 4.0) : 0.0), 0);
        const double t0 = U(-0.1, 1.1) * p.T, t1 = t0 + U(0.0, 0.6) * p.T;
        double v[2], a[2];
        fw_profile_range(&p, t0, t1, v, a);
        double vlo = 1e300, vhi = -1e300, alo = 1e300, ahi = -1e300;
        enum { N = 4000 };
        const double lo = fmax(t0, 0.0), hi = fmin(t1, p.T);
        for (int i = 0; i <= N && hi >= lo; ++i) {
            double vi, ai;
            by_hand(&p, lo + (hi - lo) * i / N, &vi, &ai);
            assert_true(vi >= v[0] - 1e-12 && vi <= v[1] + 1e-12);
            assert_true(ai >= a[0] - 1e-12 && ai <= a[1] + 1e-12);
            vlo = fmin(vlo, vi);
            vhi = fmax(vhi, vi);
            alo = fmin(alo, ai);
            ahi = fmax(ahi, ai);
        }
        if (!(hi >= lo))
            continue;
        const double jerk = 2.0 * TSE_PI * p.V / (p.Ta * p.Ta), gap = (hi - lo) / N;
        assert_true(v[0] >= vlo - 2.0 * p.V / p.Ta * gap - 1e-9 && v[1] <= vhi + 2.0 * p.V / p.Ta * gap + 1e-9);
        assert_true(a[0] >= alo - jerk * gap - 1e-9 && a[1] <= ahi + jerk * gap + 1e-9);
    }
}

static void test_invalid(void **state)
{
    (void)state;
    fw_profile p;
    assert_int_equal(fw_profile_plan(&p, -1.0, 1, 1, 1, 0), -1);
    assert_int_equal(fw_profile_plan(&p, 1.0, 0, 1, 1, 0), -1);
    assert_int_equal(fw_profile_plan(&p, 1.0, 1, NAN, 1, 0), -1);
    assert_int_equal(fw_profile_plan(&p, 1.0, 1, 1, INFINITY, 0), -1);
    assert_int_equal(fw_profile_plan(&p, 1.0, 1, 1, 1, -1), -1);
    assert_int_equal(fw_profile_plan(&p, 0.0, 1, 1, 1, 0.5), 0); /* a null move lasts its duration */
    assert_true(p.T == 0.5);
    double x, v, a;
    fw_profile_eval(&p, 0.25, &x, &v, &a);
    assert_true(x == 0.0 && v == 0.0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_random_profiles),
        cmocka_unit_test(test_range),
        cmocka_unit_test(test_invalid),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
