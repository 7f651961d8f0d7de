/* An oracle independent of the library's solver: each scissor's two conics reduced to a quartic
 * in m = (s_A - u) + (s_B - v) with coefficients expanded by hand, all four roots by Durand-Kerner
 * in complex long double, each real one polished by Newton on the original pair in long double.
 * Thousands of random poses; where the library says ok and every mu >= 0.1, its slides must match
 * within 1e-9 m, and it must never call a scissor unreachable that has a branch solution. */
#include <complex.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>

#include "tse/ik.h"

typedef long double ld;

static const ld L = 1.727L, K1 = 0.2647L, K3 = 0.0186L, K4 = 0.11765L;
#define ETA (3.14159265358979323846264338327950288L / 6)

typedef struct {
    int n;        /* branch solutions found */
    ld sa[4], sb[4];
} branch;

static ld F1(ld sa, ld sb, ld u, ld v) { return sa * sa - 2 * u * sa - sb * sb + 2 * v * sb; }

static void solve_scissor(int i, const ld C[3], branch *out)
{
    const ld beta = (ld)i * 2 * 3.14159265358979323846264338327950288L / 3;
    const ld er[2] = {cosl(beta), sinl(beta)}, et[2] = {-sinl(beta), cosl(beta)};
    const ld a[2] = {cosl(ETA) * et[0] + sinl(ETA) * er[0], cosl(ETA) * et[1] + sinl(ETA) * er[1]};
    const ld b[2] = {-cosl(ETA) * et[0] + sinl(ETA) * er[0], -cosl(ETA) * et[1] + sinl(ETA) * er[1]};
    const ld d[3] = {C[0] - K3 * L * er[0], C[1] - K3 * L * er[1], C[2]};
    const ld u = d[0] * a[0] + d[1] * a[1], v = d[0] * b[0] + d[1] * b[1];
    const ld rho2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    const ld l0 = K1 * L, g = (1 - (L / l0) * (L / l0)) / 4, c = cosl(2 * ETA);
    const ld delta = u * u - v * v, K = rho2 - L * L - u * u;
    /* (m^2 + delta)^2 + 4 K m^2 - g (P^2 + Q^2 + 2 c P Q), expanded by hand. */
    ld coef[5];
    coef[4] = 1 - 2 * g * (1 + c);
    coef[3] = -4 * g * (1 + c) * (u + v);
    coef[2] = 2 * delta + 4 * K - 4 * g * (u * u + v * v + 2 * c * u * v);
    coef[1] = -4 * g * delta * (u - v) * (1 - c);
    coef[0] = delta * delta * (1 - 2 * g * (1 - c));
    long double complex z[4];
    for (int k = 0; k < 4; ++k)
        z[k] = cpowl(0.4L + 0.9L * I, k);
    ld scale = 0;
    for (int k = 0; k < 4; ++k)
        scale = fmaxl(scale, fabsl(coef[k] / coef[4]));
    for (int it = 0; it < 2000; ++it) {
        ld moved = 0;
        for (int k = 0; k < 4; ++k) {
            long double complex p = coef[4];
            for (int j = 3; j >= 0; --j)
                p = p * z[k] + coef[j];
            long double complex den = coef[4];
            for (int j = 0; j < 4; ++j)
                if (j != k)
                    den *= z[k] - z[j];
            const long double complex step = p / den;
            z[k] -= step;
            moved += cabsl(step);
        }
        if (moved < 1e-17L * (1 + scale))
            break; /* the roots are then far closer than the Newton polish needs */
    }
    out->n = 0;
    for (int k = 0; k < 4; ++k) {
        if (fabsl(cimagl(z[k])) > 1e-7L * (1 + cabsl(z[k])))
            continue;
        const ld m = creall(z[k]);
        if (fabsl(m) < 1e-15L)
            continue;
        ld sa = (m * m + 2 * u * m + delta) / (2 * m), sb = (m * m + 2 * v * m - delta) / (2 * m);
        ld M00 = 0, M01 = 0, M10 = 0, M11 = 0;
        for (int it = 0; it < 50; ++it) {
            const ld f1 = F1(sa, sb, u, v);
            const ld f2 = sa * sa - 2 * u * sa + rho2 - L * L - g * (sa * sa + sb * sb + 2 * c * sa * sb);
            M00 = 2 * (sa - u);
            M01 = -2 * (sb - v);
            M10 = 2 * (sa - u) - 2 * g * (sa + c * sb);
            M11 = -2 * g * (sb + c * sa);
            const ld det = M00 * M11 - M01 * M10;
            if (det == 0)
                break;
            sa -= (M11 * f1 - M01 * f2) / det;
            sb -= (M00 * f2 - M10 * f1) / det;
        }
        const ld det = M00 * M11 - M01 * M10;
        if (det > 0 && sa > 0 && sb > 0) {
            out->sa[out->n] = sa;
            out->sb[out->n] = sb;
            ++out->n;
        }
    }
}

static void apex(const double p[6], ld C[3][3])
{
    const ld cr = cosl(p[3]), sr = sinl(p[3]), cp = cosl(p[4]), sp = sinl(p[4]), cy = cosl(p[5]), sy = sinl(p[5]);
    /* First two columns of Rz(yaw) Ry(pitch) Rx(roll). */
    const ld c0[3] = {cy * cp, sy * cp, -sp};
    const ld c1[3] = {cy * sp * sr - sy * cr, sy * sp * sr + cy * cr, cp * sr};
    for (int i = 0; i < 3; ++i) {
        const ld beta = (ld)i * 2 * 3.14159265358979323846264338327950288L / 3;
        for (int k = 0; k < 3; ++k)
            C[i][k] = (ld)p[k] + K4 * L * (c0[k] * cosl(beta) + c1[k] * sinl(beta));
    }
}

static double U(double a, double b) { return a + (b - a) * rand() / (double)RAND_MAX; }

static void test_against_oracle(void **state)
{
    (void)state;
    tse_params prm;
    tse_params_default(&prm);
    tse_geometry G;
    assert_int_equal(tse_geometry_init(&G, &prm), TSE_PARAM_OK);
    srand(1234);
    int compared = 0, ok = 0, unreachable = 0;
    double worst = 0, worst_warm = 0;
    for (int n = 0; n < 6000; ++n) {
        const double p[6] = {U(-0.45, 0.45), U(-0.45, 0.45), U(0.2, 1.7), U(-0.35, 0.35), U(-0.35, 0.35), U(-1.0, 1.0)};
        tse_ik_result r;
        tse_ik(&G, p, NULL, &r);
        ld C[3][3];
        apex(p, C);
        branch br[3];
        for (int i = 0; i < 3; ++i)
            solve_scissor(i, C[i], &br[i]);
        if (r.status == TSE_UNREACHABLE) {
            /* The named scissor truly has no branch solution. */
            assert_int_equal(br[r.scissor - 1].n, 0);
            ++unreachable;
        }
        assert_int_not_equal(r.status, TSE_NOCONVERGE);
        if (r.status != TSE_OK)
            continue;
        ++ok;
        if (r.mu[0] < 0.1 || r.mu[1] < 0.1 || r.mu[2] < 0.1)
            continue;
        for (int i = 0; i < 3; ++i) {
            assert_true(br[i].n >= 1);
            /* Within the stroke and the stops there is one branch solution in practice; the
             * library's must be one of the oracle's. */
            double best = INFINITY;
            for (int k = 0; k < br[i].n; ++k) {
                const double e = fmax(fabs((double)(br[i].sa[k] - (ld)r.q[2 * i])), fabs((double)(br[i].sb[k] - (ld)r.q[2 * i + 1])));
                best = fmin(best, e);
            }
            assert_true(best <= 1e-9);
            worst = fmax(worst, best);
        }
        /* Warm-started, as the control loop runs it: seeded a few millimetres off. */
        tse_real seed[6];
        for (int k = 0; k < 6; ++k)
            seed[k] = r.q[k] + (tse_real)U(-3e-3, 3e-3);
        tse_ik_result w;
        assert_int_equal(tse_ik(&G, p, seed, &w), TSE_OK);
        for (int i = 0; i < 3; ++i) {
            double best = INFINITY;
            for (int k = 0; k < br[i].n; ++k)
                best = fmin(best, fmax(fabs((double)(br[i].sa[k] - (ld)w.q[2 * i])), fabs((double)(br[i].sb[k] - (ld)w.q[2 * i + 1]))));
            assert_true(best <= 1e-9);
            worst_warm = fmax(worst_warm, best);
        }
        ++compared;
    }
    print_message("oracle: %d poses compared (ok %d, unreachable %d), worst slide error %.3g m cold, %.3g m warm\n",
                  compared, ok, unreachable, worst, worst_warm);
    assert_true(compared >= 1000);
    assert_true(unreachable >= 100);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_against_oracle)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
