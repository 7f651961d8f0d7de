/* The float build (the board's) against the double build on the same poses: within the
 * contract's 2e-6 m wherever mu >= 0.1, and the same verdict away from the limits. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>

#include "tse/ik.h"

int ik_float(const double pose[6], double q[6], double mu[3]);

static double U(double a, double b) { return a + (b - a) * rand() / (double)RAND_MAX; }

static void test_float_vs_double(void **state)
{
    (void)state;
    tse_params p;
    tse_params_default(&p);
    tse_geometry g;
    assert_int_equal(tse_geometry_init(&g, &p), TSE_PARAM_OK);
    srand(99);
    int compared = 0;
    double worst = 0;
    for (int n = 0; n < 5000; ++n) {
        const double pose[6] = {U(-0.35, 0.35), U(-0.35, 0.35), U(0.35, 1.6), U(-0.3, 0.3), U(-0.3, 0.3), U(-0.8, 0.8)};
        tse_ik_result r;
        tse_ik(&g, pose, NULL, &r);
        double qf[6], muf[3];
        const int sf = ik_float(pose, qf, muf);
        if (r.status != TSE_OK || sf != TSE_OK)
            continue;
        if (r.mu[0] < 0.1 || r.mu[1] < 0.1 || r.mu[2] < 0.1)
            continue;
        for (int k = 0; k < 6; ++k) {
            const double e = fabs(qf[k] - r.q[k]);
            assert_true(e <= 2e-6);
            worst = fmax(worst, e);
        }
        ++compared;
    }
    print_message("float vs double: %d poses, worst slide difference %.3g m\n", compared, worst);
    assert_true(compared > 1000);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_float_vs_double)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
