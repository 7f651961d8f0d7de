/* The library's own sine and cosine (kinematics/src/trig.h) against long double sinl and cosl:
 * within 1.1 ulp of the exact value where no reduction is needed (|x| <= pi/4; trig.h bounds the
 * cosine's rounding by 1.06 ulp there), two up to a few turns, three wherever the reduction runs
 * (up to its limit), and the C library's own answer beyond that, for infinities and for NaN. */
#include "test_common.h"
#include "trig.h"

#define PI_D 3.14159265358979323846

static tse_real next_up(tse_real x)
{
#if TSE_REAL_FLOAT
    return nextafterf(x, INFINITY);
#else
    return nextafter(x, INFINITY);
#endif
}

/* The spacing of this precision's numbers at |y|, taken as the smallest normal number's below it. */
static long double ulp_of(long double y)
{
    const int digits = IS_FLOAT ? FLT_MANT_DIG : DBL_MANT_DIG;
    const long double tiny = IS_FLOAT ? FLT_MIN : DBL_MIN;
    int e;
    frexpl(fmaxl(fabsl(y), tiny), &e);
    return ldexpl(1.0L, e - digits);
}

typedef struct {
    double worst; /* in ulps */
    double at;
    long n;
} trig_stats;

/* One argument: both results against the long double reference, in ulps of the exact value. */
static void check_one(tse_real x, double max_ulps, trig_stats *st)
{
    tse_real s, c;
    tse_sincos(x, &s, &c);
    const long double xs = (long double)x;
    const long double es = fabsl((long double)s - sinl(xs)) / ulp_of(sinl(xs));
    const long double ec = fabsl((long double)c - cosl(xs)) / ulp_of(cosl(xs));
    const double e = (double)fmaxl(es, ec);
    if (!(e <= max_ulps)) {
        print_error("sincos(%.17g) = (%.17g, %.17g): %.3g ulp off (sinl %.21Lg, cosl %.21Lg), allowed %.3g\n",
                    (double)x, (double)s, (double)c, e, sinl(xs), cosl(xs), max_ulps);
        fail();
    }
    if (e > st->worst) {
        st->worst = e;
        st->at = (double)x;
    }
    st->n++;
}

/* n arguments with magnitudes spread evenly on a log scale over [lo, hi], both signs. */
static void check_range(double lo, double hi, int n, double max_ulps, uint64_t *seed)
{
    trig_stats st = {0.0, 0.0, 0};
    for (int k = 0; k < n; ++k) {
        const double m = exp(log(lo) + (log(hi) - log(lo)) * rng_range(seed, 0.0, 1.0));
        check_one((tse_real)(k % 2 ? -m : m), max_ulps, &st);
    }
    print_message("|x| in [%g, %g]: %ld arguments, worst %.3f ulp at %.17g (allowed %.1f)\n", lo, hi, st.n,
                  st.worst, st.at, max_ulps);
}

static void test_reduced_arguments(void **state)
{
    (void)state;
    uint64_t seed = 2024;
    check_range(1e-30, 1e-3, 20000, 1.1, &seed);
    check_range(1e-3, 0.785, 200000, 1.1, &seed);
}

static void test_few_turns(void **state)
{
    (void)state;
    uint64_t seed = 77;
    check_range(0.786, 2.0 * PI_D, 200000, 2.0, &seed);
    /* next to the multiples of pi/2, where the reduced argument is small and carries the result */
    trig_stats st = {0.0, 0.0, 0};
    for (int q = 1; q <= 400; ++q) {
        tse_real x = (tse_real)(q * (PI_D / 2.0));
        for (int k = 0; k < 40; ++k) {
            check_one(x, 2.0, &st);
            check_one(-x, 2.0, &st);
            x = next_up(x);
        }
    }
    print_message("next to k pi/2, k <= 400: %ld arguments, worst %.3f ulp at %.17g\n", st.n, st.worst, st.at);
}

static void test_large_arguments(void **state)
{
    (void)state;
    uint64_t seed = 4242;
    /* up to the reduction's limit, and beyond it where the C library answers */
    check_range(2.0 * PI_D, IS_FLOAT ? 3.0e3 : 1.6e6, 200000, 3.0, &seed);
    check_range(IS_FLOAT ? 3.0e3 : 1.6e6, 1e30, 20000, 3.0, &seed);
}

static void test_special_values(void **state)
{
    (void)state;
    tse_real s, c;
    tse_sincos(TSE_R(0.0), &s, &c);
    assert_true(s == TSE_R(0.0) && c == TSE_R(1.0));
    tse_sincos(-TSE_R(0.0), &s, &c);
    assert_true(s == TSE_R(0.0) && c == TSE_R(1.0));
    const tse_real bad[3] = {(tse_real)INFINITY, -(tse_real)INFINITY, (tse_real)NAN};
    for (int k = 0; k < 3; ++k) {
        tse_sincos(bad[k], &s, &c);
        assert_true(isnan(s) && isnan(c));
    }
    /* the largest finite number goes to the C library, as every argument beyond the reduction */
    trig_stats st = {0.0, 0.0, 0};
    check_one(IS_FLOAT ? FLT_MAX : DBL_MAX, 1.0, &st);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_reduced_arguments),
        cmocka_unit_test(test_few_turns),
        cmocka_unit_test(test_large_arguments),
        cmocka_unit_test(test_special_values),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
