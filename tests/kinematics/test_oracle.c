/* The library against the independent long-double reference (oracle.c) on thousands of random
 * poses with a fixed seed (kinematics.md, "Accuracy of an accepted pose", the status order, and
 * "unreachable therefore means: no root of that quartic gives det M > 0 with positive slides"). */
#include "test_common.h"

static const double PI = 3.14159265358979323846;

typedef struct {
    long poses, accuracy_compared, ok, ambiguous, multi;
    long status_agree, order_cases;
    long failures;
    long by_status[TSE_STATUS_COUNT];
    double max_q_err, max_mu_err, max_nu_err;
    long mu_above_1, nu_above_1;
} tally;

#define MAX_REPORTS 12

static void report(tally *t, const char *what, const tse_real pose[6], const char *fmt, ...)
{
    t->failures++;
    if (t->failures > MAX_REPORTS)
        return;
    char buf[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    print_error("%s: pose " POSE_FMT ": %s\n", what, POSE_ARGS(pose), buf);
}

/* Compare one pose; seed_q may be NULL. */
static void compare_pose(const tse_geometry *g, const orc_geom *og, const tse_real pose[6],
                         const tse_real *seed_q, const char *what, tally *t)
{
    orc_tol tol = test_orc_tol();
    orc_real po[6];
    pose_to_orc(pose, po);
    tse_ik_result r;
    tse_status st = tse_ik(g, pose, seed_q, &r);
    t->poses++;
    if (st != r.status) {
        report(t, what, pose, "return value %s differs from result status %s", st_name(st),
               st_name(r.status));
        return;
    }
    if (r.status >= 0 && r.status < TSE_STATUS_COUNT)
        t->by_status[r.status]++;
    orc_result o;
    orc_ik(og, po, NULL, &tol, &o);
    if (o.multi) {
        /* several branch solutions: the library's choice decides which is compared */
        t->multi++;
        orc_real pq[6];
        q_to_orc(r.q, pq);
        orc_ik(og, po, pq, &tol, &o);
    }

    /* never unreachable where the reference finds a clear branch solution */
    if (r.status == TSE_UNREACHABLE && r.scissor >= 1 && r.scissor <= 3) {
        int i = r.scissor - 1;
        orc_scissor_set set;
        orc_scissor(og, i, o.C[i], &tol, &set);
        for (int k = 0; k < set.n; k++) {
            const orc_sol *s = &set.branch[k];
            if (s->mu > 10 * tol.mu && s->sa > 10 * tol.len && s->sb > 10 * tol.len) {
                report(t, what, pose,
                       "unreachable on scissor %d, but the reference solves it: s = (%.12Lg, "
                       "%.12Lg), mu %.4Lg, alpha %.4Lg rad%s",
                       r.scissor, s->sa, s->sb, s->mu, acosl(s->w / (2 * og->l0)),
                       o.st[i] == TSE_OK ? " (that scissor passes every check)" : "");
                return;
            }
        }
    }
    if (r.status == TSE_NOCONVERGE) {
        report(t, what, pose, "noconverge; the reference says %s/%d", st_name(o.status),
               o.scissor);
        return;
    }

    if (o.ambiguous) {
        t->ambiguous++;
    } else {
        int any_scissor = (o.status == TSE_DEGENERATE || o.status == TSE_OK);
        if ((int)r.status != o.status || (!any_scissor && r.scissor != o.scissor)) {
            report(t, what, pose, "status %s/%d, the reference %s/%d (per scissor %s %s %s)",
                   st_name(r.status), r.scissor, st_name(o.status), o.scissor, st_name(o.st[0]),
                   st_name(o.st[1]), st_name(o.st[2]));
            return;
        }
        t->status_agree++;
        /* where some other scissor fails an earlier check than the named one */
        for (int i = 0; i < 3; i++)
            if (o.st[i] != TSE_OK && o.st[i] < o.status) {
                t->order_cases++;
                break;
            }
    }

    if (r.status == TSE_OK) {
        t->ok++;
        if (r.scissor != 0)
            report(t, what, pose, "ok with scissor %d", r.scissor);
        for (int i = 0; i < 3; i++)
            if (r.mu[i] > 1)
                t->mu_above_1++;
        if (r.nu > 1)
            t->nu_above_1++;
        for (int i = 0; i < 3; i++)
            if (!(r.mu[i] > 0 && r.mu[i] <= 1 + 4 * TSE_REAL_EPS && r.mu[i] >= g->p.mu_min))
                report(t, what, pose, "ok with mu[%d] = %.9g", i, (double)r.mu[i]);
        if (!(r.nu > 0 && r.nu <= 1 + 4 * TSE_REAL_EPS && r.nu >= g->p.nu_min))
            report(t, what, pose, "ok with nu = %.9g", (double)r.nu);
        if (o.nsol[0] < 1 || o.nsol[1] < 1 || o.nsol[2] < 1) {
            report(t, what, pose, "ok, but the reference has no branch solution (%d %d %d)",
                   o.nsol[0], o.nsol[1], o.nsol[2]);
            return;
        }
        if (o.mu[0] >= 0.1L && o.mu[1] >= 0.1L && o.mu[2] >= 0.1L) {
            t->accuracy_compared++;
            double worst = 0;
            int kw = 0;
            for (int k = 0; k < 6; k++) {
                double e = fabs((double)((orc_real)r.q[k] - o.q[k]));
                if (!(e <= worst)) {
                    worst = e;
                    kw = k;
                }
            }
            if (worst > t->max_q_err)
                t->max_q_err = worst;
            if (!(worst <= TOL_Q))
                report(t, what, pose, "q[%d] = %.17g, reference %.17Lg (error %.3g > %.1g)", kw,
                       (double)r.q[kw], o.q[kw], worst, TOL_Q);
            for (int i = 0; i < 3; i++) {
                double e = fabs((double)((orc_real)r.mu[i] - o.mu[i]));
                if (e > t->max_mu_err)
                    t->max_mu_err = e;
                if (!(e <= (IS_FLOAT ? 1e-4 : 1e-9)))
                    report(t, what, pose, "mu[%d] = %.12g, reference %.12Lg", i,
                           (double)r.mu[i], o.mu[i]);
            }
            double e = fabs((double)((orc_real)r.nu - o.nu));
            if (e > t->max_nu_err)
                t->max_nu_err = e;
            if (!(e <= (IS_FLOAT ? 1e-4 : 1e-9)))
                report(t, what, pose, "nu = %.12g, reference %.12Lg", (double)r.nu, o.nu);
        }
    }
}

static void print_tally(const char *name, const tally *t)
{
    print_message("%s: %ld poses, %ld ok, %ld compared for accuracy (max |q error| %.3g m, "
                  "mu %.3g, nu %.3g)\n",
                  name, t->poses, t->ok, t->accuracy_compared, t->max_q_err, t->max_mu_err,
                  t->max_nu_err);
    print_message("  statuses:");
    for (int s = 0; s < TSE_STATUS_COUNT; s++)
        print_message(" %s %ld", st_name(s), t->by_status[s]);
    print_message("\n  %ld statuses agree with the reference (%ld where a later scissor fails an "
                  "earlier check); %ld too close to a threshold to call; %ld with several branch "
                  "solutions; %ld failures\n",
                  t->status_agree, t->order_cases, t->ambiguous, t->multi, t->failures);
    if (t->mu_above_1 || t->nu_above_1)
        print_message("  note: %ld mu and %ld nu above 1 by rounding (accepted within 4 eps)\n",
                      t->mu_above_1, t->nu_above_1);
}

static void random_pose(uint64_t *seed, double r_max, double z_lo, double z_hi, double tilt,
                        double yaw, tse_real pose[6])
{
    double r = r_max * sqrt(rng_unit(seed)), ph = rng_range(seed, -PI, PI);
    set_pose(pose, r * cos(ph), r * sin(ph), rng_range(seed, z_lo, z_hi),
             rng_range(seed, -tilt, tilt), rng_range(seed, -tilt, tilt),
             rng_range(seed, -yaw, yaw));
}

/* Inside the workspace: accuracy of every accepted pose with mu >= 0.1. */
static void test_random_workspace_cold(void **state)
{
    (void)state;
    tse_geometry g;
    orc_geom og;
    test_default_geometries(&g, &og);
    tally t;
    memset(&t, 0, sizeof t);
    uint64_t seed = 20240601;
    for (int n = 0; n < 12000; n++) {
        tse_real pose[6];
        random_pose(&seed, 0.45, 0.3, 1.65, 0.35, 0.8, pose);
        compare_pose(&g, &og, pose, NULL, "workspace, cold", &t);
    }
    print_tally("workspace, cold start", &t);
    assert_int_equal(t.failures, 0);
    assert_true(t.accuracy_compared >= 3000);
}

/* Strongly tilted and far poses: the cold start has to fall back; the status must still be the
 * reference's. */
static void test_random_wide_cold(void **state)
{
    (void)state;
    tse_geometry g;
    orc_geom og;
    test_default_geometries(&g, &og);
    tally t;
    memset(&t, 0, sizeof t);
    uint64_t seed = 77;
    for (int n = 0; n < 12000; n++) {
        tse_real pose[6];
        random_pose(&seed, 0.8, -0.2, 1.9, 0.9, 1.5, pose);
        compare_pose(&g, &og, pose, NULL, "wide, cold", &t);
    }
    print_tally("wide, cold start", &t);
    assert_int_equal(t.failures, 0);
    assert_true(t.ok > 500);
}

/* Trajectories: each pose warm-started from the previous solution, as the controller does. */
static void test_random_trajectories_warm(void **state)
{
    (void)state;
    tse_geometry g;
    orc_geom og;
    test_default_geometries(&g, &og);
    tally t;
    memset(&t, 0, sizeof t);
    uint64_t seed = 4242;
    for (int traj = 0; traj < 60; traj++) {
        tse_real pose[6];
        random_pose(&seed, 0.3, 0.5, 1.4, 0.2, 0.5, pose);
        tse_ik_result prev;
        tse_ik(&g, pose, NULL, &prev);
        double step = traj % 2 ? 0.002 : 0.02;
        for (int n = 0; n < 100; n++) {
            for (int k = 0; k < 6; k++)
                pose[k] += (tse_real)(step * rng_range(&seed, -1, 1) * (k < 3 ? 1.0 : 0.5));
            const tse_real *seed_q = all_finite_q(prev.q) ? prev.q : NULL;
            compare_pose(&g, &og, pose, seed_q, "trajectory, warm", &t);
            tse_ik(&g, pose, seed_q, &prev);
        }
    }
    print_tally("trajectories, warm start", &t);
    assert_int_equal(t.failures, 0);
    assert_true(t.accuracy_compared >= 3000);
}

/* Other designs: the contract holds for any valid parameter set, not only the prototype. */
static void test_random_other_designs(void **state)
{
    (void)state;
    uint64_t seed = 99;
    tally t;
    memset(&t, 0, sizeof t);
    for (int d = 0; d < 6; d++) {
        tse_params p;
        test_other_design(&seed, d, &p);
        tse_geometry g;
        orc_geom og;
        test_geometries(&p, &g, &og);
        for (int n = 0; n < 1500; n++) {
            tse_real pose[6];
            random_pose(&seed, 0.4, 0.2, 1.7, 0.4, 0.8, pose);
            compare_pose(&g, &og, pose, NULL, "other design", &t);
        }
    }
    print_tally("other designs, cold start", &t);
    assert_int_equal(t.failures, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_random_workspace_cold),
        cmocka_unit_test(test_random_wide_cold),
        cmocka_unit_test(test_random_trajectories_warm),
        cmocka_unit_test(test_random_other_designs),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
