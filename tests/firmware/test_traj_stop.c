/* A trajectory's stop ramp (fw/traj_stop.h) against its law integrated here on its own: the rate r
 * braking along r' = -(amax / v) (1 - m r) from 1 to 0, by small explicit steps in double. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "fw/traj_stop.h"

/* The law's end and the path time it covers, by 1e-7 s steps of the differential equation. */
static void integrate(double v, double amax, double *T, double *D)
{
    const double m = 0.95, h = 1e-7;
    double r = 1.0, t = 0.0, d = 0.0;
    while (r > 0.0) {
        const double dr = -(amax / v) * (1.0 - m * r) * h;
        d += (r + 0.5 * dr > 0.0 ? r + 0.5 * dr : 0.5 * r) * h;
        r += dr;
        t += h;
    }
    *T = t;
    *D = d;
}

static void test_constant_is_the_margins_log(void **state)
{
    (void)state;
    /* The docs' m is 0.95: the constant and the margin it comes from agree. */
    assert_true(fabs((double)FW_PATH_MARGIN - 0.95) < 1e-7);
    assert_true(fabs((double)FW_TRAJ_STOP_LN - log(1.0 / (1.0 - 0.95))) < 1e-6);
}

static void test_length_and_reach_follow_the_law(void **state)
{
    (void)state;
    static const double cases[][2] = {{0.1, 1.0}, {0.0695, 1.0}, {0.5, 4.0}, {0.02, 0.25}};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        double T, D;
        integrate(cases[i][0], cases[i][1], &T, &D);
        const double T_fw = (double)fw_traj_stop_time((tse_real)cases[i][0], (tse_real)cases[i][1], (tse_real)0.0);
        const double D_fw = (double)fw_traj_stop_reach((tse_real)T_fw);
        print_message("v %.4f m/s, amax %.2f m/s^2: T %.5f s (law %.5f), path %.5f s (law %.5f)\n", cases[i][0],
                      cases[i][1], T_fw, T, D_fw, D);
        assert_true(fabs(T_fw / T - 1.0) < 1e-4);
        assert_true(fabs(D_fw / D - 1.0) < 1e-4);
        /* The docs' figures: 3.15 v / amax long, 2.27 v / amax of path. */
        assert_true(fabs(T_fw * cases[i][1] / cases[i][0] - 3.15) < 0.01);
        assert_true(fabs(D_fw * cases[i][1] / cases[i][0] - 2.27) < 0.01);
    }
    /* The shortest stop is kept. */
    assert_true(fabs((double)fw_traj_stop_time((tse_real)1e-4, (tse_real)1.0, (tse_real)0.02) - 0.02) < 1e-9);
}

/* Run a control period at a time (1 ms), the ramp's braking and the path's own acceleration (its
 * share m of the limit, scaled by r, as at a row's change of speed) stay within the limit but for
 * the period's discretisation, and r is where the law puts it. */
static void test_the_ramp_as_it_runs(void **state)
{
    (void)state;
    const double v = 0.1, amax = 1.0, dt = 1e-3, m = 0.95;
    const tse_real T = fw_traj_stop_time((tse_real)v, (tse_real)amax, (tse_real)0.02);
    fw_traj_stop s;
    fw_traj_stop_begin(&s, T, (tse_real)dt);
    double r_prev = 1.0, worst = 0.0;
    int n = 0;
    for (double t = dt; t < (double)T; t += dt, ++n) {
        const double r = (double)fw_traj_stop_next(&s);
        /* 1 - m r = (1 - m) e^(k t), k = m amax / v. */
        const double exact = (1.0 - (1.0 - m) * exp(m * amax / v * t)) / m;
        assert_true(fabs(r - (exact > 0.0 ? exact : 0.0)) < 1e-5);
        assert_true(r <= r_prev);
        /* Over the period: |r'| v and the path's m r at its middle, of the limit. */
        const double braking = (r_prev - r) / dt * v / amax;
        worst = fmax(worst, braking + m * 0.5 * (r_prev + r));
        r_prev = r;
    }
    print_message("%d periods, braking and path at most %.4f of slide_amax\n", n, worst);
    assert_true(n > 300);
    assert_true(worst <= 1.0 + 1e-3);
    assert_true(r_prev < 0.01);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_constant_is_the_margins_log),
        cmocka_unit_test(test_length_and_reach_follow_the_law),
        cmocka_unit_test(test_the_ramp_as_it_runs),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
