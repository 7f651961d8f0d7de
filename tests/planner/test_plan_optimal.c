/* Planned durations against the time-optimal motion found independently of the planner.
 *
 * A straight vertical line: on the axis all six slides are equal (docs/kinematics.md), so the
 * slides' limits act on one coordinate s(Z), and the fastest motion from rest to rest is the
 * bang-bang one in s: T = |ds| / v + v / a when |ds| >= v^2 / a, else 2 sqrt(|ds| / a), with v the
 * slide speed limit in effect and a slide_amax.  s(Z) by hand algebra: with u0 = (r_top - r_act)
 * sin(eta), rho2 = (r_top - r_act)^2 + Z^2, g = (1 - (L / l0)^2) / 4 and A = 1 - 2 g (1 + cos 2 eta),
 * F2 becomes A s^2 - 2 u0 s + rho2 - L^2 = 0, whose larger root is the physical one.
 *
 * A pure yaw: the slides of one kind move together but not linearly in the angle, so the optimum
 * comes from an independent integration in the phase plane (the classical forward and backward
 * integration at the extreme accelerations, clamped to the speed limit curve) over the slides the
 * inverse kinematics gives along the rotation.
 *
 * At rows 10 ms and 5 ms apart, the validator's 10 ms stride sees the path's own acceleration; at
 * rows 20 ms apart (tse-kin plan's default) it sees each row's change of a slide's speed whole
 * over its stride, so the rows may change a slide's speed by slide_amax x 10 ms each, and their
 * optimum is the same motion at an acceleration of slide_amax x 10 ms / 20 ms.  Rows 10 ms apart
 * or closer are planned with slide_amax at 4 m/s^2: with the default 1 m/s^2 the controller's queue
 * of 32 rows would hold less path than a stop from full speed needs (plan.h). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "fw/limits.h"
#include "plan_support.h"
#include "tse/ik.h"
#include "tse/jacobian.h"

static double v_lim;

/* The parameter set rows `period` apart are planned with: the defaults, slide_amax at 4 m/s^2 for
 * rows 10 ms apart or closer. */
static fw_param_set set_for(double period)
{
    fw_param_set s;
    fw_params_default(&s);
    if (period <= 0.01)
        s.v[FP_SLIDE_AMAX] = 4000000;
    return s;
}

static int setup(void **state)
{
    (void)state;
    const fw_param_set s = set_for(0.02);
    fw_speed_limit v;
    if (fw_speed_limit_from_params(&s, FW_STEP_HZ, FW_SEGMENT_HZ, &v) != 0)
        return -1;
    v_lim = (double)v.vmax;
    return 0;
}

static double axis_slide(double z)
{
    fw_param_set s;
    fw_params_default(&s);
    const double L = s.v[FP_L] * 1e-6, l0 = s.v[FP_K1] * 1e-6 * L, eta = s.v[FP_ETA] * 1e-6;
    const double d = (s.v[FP_K4] - s.v[FP_K3]) * 1e-6 * L;
    const double g = (1.0 - (L / l0) * (L / l0)) / 4.0, A = 1.0 - 2.0 * g * (1.0 + cos(2.0 * eta));
    const double u0 = d * sin(eta);
    return (u0 + sqrt(u0 * u0 - A * (d * d + z * z - L * L))) / A;
}

/* The acceleration the rows `period` apart may have, as the validator's stride sees them. */
static double a_rows(double period)
{
    return (double)FW_PATH_MARGIN * set_for(period).v[FP_SLIDE_AMAX] * 1e-6 * fmin(1.0, 0.01 / period);
}

static double bang_bang(double ds, double a)
{
    ds = fabs(ds);
    return ds >= v_lim * v_lim / a ? ds / v_lim + v_lim / a : 2.0 * sqrt(ds / a);
}

/* The motion's duration: the last row's time less the row holding the start. */
static double planned(const plan_waypoint *wp, int n, double period)
{
    plan_options o;
    plan_options_default(&o);
    o.period = period;
    plan_result r;
    const fw_param_set s = set_for(period);
    plan *p = make_plan(&s, wp, n, &o, &r);
    assert_non_null(p);
    const double T = plan_duration(p) - plan_hold(p);
    assert_int_equal(judge_rows(&s, p, wp[0].pose).refused_row, -1);
    free_plan(p);
    return T;
}

static void check_near(const char *what, double T, double T_opt)
{
    printf("# %s: planned %.4f s, optimum %.4f s (%+.2f %%)\n", what, T, T_opt, 100.0 * (T / T_opt - 1.0));
    /* Not faster than the optimum (beyond the grid's and the rows' discretisation), within 2 %. */
    assert_true(T >= 0.995 * T_opt);
    assert_true(T <= 1.02 * T_opt);
}

static void test_vertical_line(void **state)
{
    (void)state;
    const double heights[][2] = {{0.9, 1.2}, {1.3, 0.8}, {1.0, 1.03}};
    const double periods[] = {0.02, 0.01, 0.005};
    for (size_t i = 0; i < sizeof heights / sizeof heights[0]; ++i)
        for (size_t k = 0; k < 3; ++k) {
            const plan_waypoint wp[2] = {waypoint(0, 0, heights[i][0], 0, 0, 0), waypoint(0, 0, heights[i][1], 0, 0, 0)};
            char what[96];
            snprintf(what, sizeof what, "vertical %.2f -> %.2f m, rows %.3f s apart", heights[i][0], heights[i][1],
                     periods[k]);
            check_near(what, planned(wp, 2, periods[k]),
                       bang_bang(axis_slide(heights[i][1]) - axis_slide(heights[i][0]), a_rows(periods[k])));
        }
}

/* The phase-plane optimum of the rotation about the vertical axis from yaw 0 to psi at height z. */
static double yaw_optimum(double z, double psi, double a_max)
{
    enum { M = 4000 };
    static double qp[M + 1][6], qpp[M + 1][6], y_f[M + 1], y_b[M + 1];
    tse_params kp;
    tse_params_default(&kp);
    tse_geometry g;
    assert_int_equal(tse_geometry_init(&g, &kp), TSE_PARAM_OK);
    /* Along sigma = |yaw| from 0: yaw = dir sigma. */
    const double dir = psi < 0 ? -1.0 : 1.0, h = fabs(psi) / M;
    tse_ik_result ik;
    const double *seed = NULL;
    double q[6];
    for (int i = 0; i <= M; ++i) {
        const double pose[6] = {0, 0, z, 0, 0, dir * h * i};
        double J[6][6];
        assert_int_equal(tse_ik(&g, pose, seed, &ik), TSE_OK);
        assert_int_equal(tse_jacobian(&g, pose, ik.q, J), TSE_OK);
        for (int j = 0; j < 6; ++j) {
            q[j] = ik.q[j];
            qp[i][j] = dir * J[j][5]; /* dq/dsigma */
        }
        seed = q;
    }
    for (int i = 0; i <= M; ++i) {
        const int a = i > 0 ? i - 1 : 0, b = i < M ? i + 1 : M;
        for (int j = 0; j < 6; ++j)
            qpp[i][j] = (qp[b][j] - qp[a][j]) / ((b - a) * h);
    }
    /* The speed limit curve, then the extreme accelerations psi'' at (i, y = psi'^2). */
    for (int pass = 0; pass < 2; ++pass) {
        double *y = pass == 0 ? y_f : y_b;
        y[pass == 0 ? 0 : M] = 0.0;
        for (int n = 0; n < M; ++n) {
            const int i = pass == 0 ? n : M - n, next = pass == 0 ? i + 1 : i - 1;
            double lo = -INFINITY, hi = INFINITY, ycap = INFINITY;
            for (int j = 0; j < 6; ++j) {
                ycap = fmin(ycap, pow(v_lim / fabs(qp[next][j]), 2));
                const double u1 = (-a_max - qpp[i][j] * y[i]) / qp[i][j], u2 = (a_max - qpp[i][j] * y[i]) / qp[i][j];
                lo = fmax(lo, fmin(u1, u2));
                hi = fmin(hi, fmax(u1, u2));
            }
            assert_true(lo <= hi); /* the speed limit keeps it below the acceleration's own bound */
            /* Forward: the greatest acceleration; backward (psi decreasing): the greatest braking. */
            y[next] = fmin(fmax(y[i] + 2.0 * h * (pass == 0 ? hi : -lo), 0.0), ycap);
        }
    }
    double T = 0.0;
    for (int i = 0; i < M; ++i)
        T += 2.0 * h / (sqrt(fmin(y_f[i], y_b[i])) + sqrt(fmin(y_f[i + 1], y_b[i + 1])));
    return T;
}

static void test_pure_yaw(void **state)
{
    (void)state;
    const double cases[][2] = {{1.0, 0.5}, {1.2, -0.3}, {0.9, 0.05}};
    const double periods[] = {0.02, 0.01, 0.005};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i)
        for (size_t k = 0; k < 3; ++k) {
            const plan_waypoint wp[2] = {waypoint(0, 0, cases[i][0], 0, 0, 0), waypoint(0, 0, cases[i][0], 0, 0, cases[i][1])};
            char what[96];
            snprintf(what, sizeof what, "yaw 0 -> %.2f rad at z = %.2f m, rows %.3f s apart", cases[i][1], cases[i][0],
                     periods[k]);
            check_near(what, planned(wp, 2, periods[k]), yaw_optimum(cases[i][0], cases[i][1], a_rows(periods[k])));
        }
}

/* With a jerk limit J the law is smoothed over a window of A / J to 2 A / J (A the acceleration the
 * rows may have, with the planner's margin), and the motion lasts that much longer than without.
 * For a line long enough to reach A and cruise, the fastest jerk-limited motion of one slide from
 * rest to rest is the bang-bang one plus A / J (its acceleration ramps take A / J each, and each
 * costs half of that): the plan is within 3 % of it.  Each slide's jerk, measured from the rows
 * 5 ms apart by divided differences of the slides the hand algebra gives, is within J and near
 * it. */
static void test_jerk_limited(void **state)
{
    (void)state;
    const double period = 0.005;
    const fw_param_set s = set_for(period);
    plan_options o;
    plan_options_default(&o);
    o.period = period;
    /* The controller's own slide jerk limit: slide_amax x plate_jmax / plate_amax, 40 m/s^3 here. */
    const double J = s.v[FP_SLIDE_AMAX] * 1e-6 * ((double)s.v[FP_PLATE_JMAX] / (double)s.v[FP_PLATE_AMAX]);
    const double heights[][2] = {{0.9, 1.2}, {1.3, 0.8}, {1.0, 1.03}};
    for (size_t i = 0; i < sizeof heights / sizeof heights[0]; ++i) {
        const plan_waypoint wp[2] = {waypoint(0, 0, heights[i][0], 0, 0, 0), waypoint(0, 0, heights[i][1], 0, 0, 0)};
        plan_result r;
        o.jmax = 0.0;
        plan *p0 = make_plan(&s, wp, 2, &o, &r);
        assert_non_null(p0);
        o.jmax = PLAN_JMAX_CONTROLLER; /* asked for as the controller's: J */
        plan *p = make_plan(&s, wp, 2, &o, &r);
        assert_non_null(p);
        plan_stats st;
        assert_int_equal(plan_measure(p, &st), 0);
        assert_true(fabs(st.j_limit - J) < 1e-9 * J);
        assert_int_equal(judge_rows(&s, p, wp[0].pose).refused_row, -1);
        const double A = a_rows(period) * o.a_margin, Tj = A / J;
        const double longer = plan_duration(p) - plan_duration(p0), T = plan_duration(p) - plan_hold(p);
        const double T_opt = bang_bang(axis_slide(heights[i][1]) - axis_slide(heights[i][0]), a_rows(period)) +
                             a_rows(period) / J;
        /* The slides' jerk: third differences of the rows' slides, rows evenly 5 ms apart. */
        double q[4] = {0}, t[4] = {0}, worst = 0.0;
        int have = 0;
        plan_cursor c;
        plan_row row;
        for (plan_rows_begin(p, &c); plan_rows_next(p, &c, &row);) {
            memmove(q, q + 1, 3 * sizeof q[0]);
            memmove(t, t + 1, 3 * sizeof t[0]);
            q[3] = axis_slide(row.pose[2]);
            t[3] = row.t;
            /* Six times the third divided difference (rows are evenly spaced within a stretch only). */
            if (++have >= 5) {
                double d[4];
                memcpy(d, q, sizeof d);
                for (int k = 1; k < 4; ++k)
                    for (int m = 3; m >= k; --m)
                        d[m] = (d[m] - d[m - 1]) / (t[m] - t[m - k]);
                worst = fmax(worst, 6.0 * fabs(d[3]));
            }
        }
        printf("# jerk-limited vertical %.2f -> %.2f m, rows %.3f s apart: %.4f s (%.4f s longer, A / J %.4f s), "
               "jerk-limited optimum %.4f s (%+.2f %%); slide jerk at most %.1f of %.1f m/s^3\n",
               heights[i][0], heights[i][1], period, T, longer, Tj, T_opt, 100.0 * (T / T_opt - 1.0), worst, J);
        assert_true(longer >= Tj - 0.001 && longer <= 2.0 * Tj + 0.001);
        if (i < 2) /* (the short line reaches neither A nor the speed limit) */
            assert_true(T >= 0.995 * T_opt && T <= 1.03 * T_opt);
        assert_true(worst <= 1.05 * J);
        assert_true(worst >= 0.8 * J); /* the law does use its jerk */
        free_plan(p);
        free_plan(p0);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_vertical_line),
        cmocka_unit_test(test_pure_yaw),
        cmocka_unit_test(test_jerk_limited),
    };
    return cmocka_run_group_tests(tests, setup, NULL);
}
