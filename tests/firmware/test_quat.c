/* Quaternions against the kinematics' rotation matrix R = Rz Ry Rx. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>

#include "fw/quat.h"
#include "tse/ik.h"

static double U(double a, double b) { return a + (b - a) * rand() / (double)RAND_MAX; }

/* Rotation matrix of a unit quaternion, from its definition. */
static void quat_matrix(const double q[4], double R[3][3])
{
    const double w = q[0], x = q[1], y = q[2], z = q[3];
    R[0][0] = 1 - 2 * (y * y + z * z);
    R[0][1] = 2 * (x * y - w * z);
    R[0][2] = 2 * (x * z + w * y);
    R[1][0] = 2 * (x * y + w * z);
    R[1][1] = 1 - 2 * (x * x + z * z);
    R[1][2] = 2 * (y * z - w * x);
    R[2][0] = 2 * (x * z - w * y);
    R[2][1] = 2 * (y * z + w * x);
    R[2][2] = 1 - 2 * (x * x + y * y);
}

static void test_matches_rotation(void **state)
{
    (void)state;
    srand(5);
    for (int rep = 0; rep < 1000; ++rep) {
        const double r = U(-3, 3), p = U(-1.5, 1.5), y = U(-3, 3);
        double q[4], Rq[3][3], R[3][3], rpy[3];
        fw_quat_from_rpy(r, p, y, q);
        quat_matrix(q, Rq);
        tse_rotation(r, p, y, R);
        for (int i = 0; i < 3; ++i)
            for (int k = 0; k < 3; ++k)
                assert_true(fabs(Rq[i][k] - R[i][k]) < 1e-14);
        fw_quat_to_rpy(q, rpy);
        assert_true(fabs(rpy[0] - r) < 1e-12 && fabs(rpy[1] - p) < 1e-12 && fabs(rpy[2] - y) < 1e-12);
    }
}

static void test_slerp(void **state)
{
    (void)state;
    srand(6);
    for (int rep = 0; rep < 1000; ++rep) {
        double a[4], b[4], m[4];
        fw_quat_from_rpy(U(-1, 1), U(-1, 1), U(-3, 3), a);
        fw_quat_from_rpy(U(-1, 1), U(-1, 1), U(-3, 3), b);
        const double total = fw_quat_angle(a, b);
        assert_true(total >= 0 && total <= TSE_PI + 1e-12);
        const double u = U(0, 1);
        fw_quat_slerp(a, b, u, m);
        /* Constant rate along one arc: the angle travelled is u of the whole, the rest 1 - u. */
        assert_true(fabs(fw_quat_angle(a, m) - u * total) < 1e-9);
        assert_true(fabs(fw_quat_angle(m, b) - (1 - u) * total) < 1e-9);
        fw_quat_slerp(a, b, 1.0, m);
        assert_true(fw_quat_angle(m, b) < 1e-9);
    }
    /* A tiny rotation takes the lerp branch and stays on the arc. */
    double a[4], b[4], m[4];
    fw_quat_from_rpy(0, 0, 0, a);
    fw_quat_from_rpy(0, 0, 1e-6, b);
    fw_quat_slerp(a, b, 0.5, m);
    double rpy[3];
    fw_quat_to_rpy(m, rpy);
    assert_true(fabs(rpy[2] - 0.5e-6) < 1e-15);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_matches_rotation),
        cmocka_unit_test(test_slerp),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
