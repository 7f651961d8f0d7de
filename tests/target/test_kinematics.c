/* The float kinematics (tse_kin_f, the board's build) on the emulated Cortex-M4F, against the
 * table gen_kin_table.c computed on the host in double precision at build time: a few hundred
 * poses in paths, covering every status of kinematics.md (ok, invalid, unreachable, below, alpha,
 * stroke, singular, degenerate), each decided with margin so that float must agree.
 *
 * - IK cold (no seed) and warm (seeded along each path with the previous float slides that are
 *   all finite, as a control loop would): status and failing scissor equal to the table's; the
 *   slides of every scissor whose margin mu >= 0.1 within 2e-6 m of the double ones (the
 *   contract's single-precision accuracy).
 * - FK from the home pose, given the double slides (rounded to float), on the accepted poses
 *   where the double FK from home returns the table's pose: the float answer is that pose within
 *   a bound derived per pose and component (see fk_case).
 * Worst errors are printed in nanometres (newlib-nano's printf has no float conversion). */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "kin_table.h"
#include "target_test.h"
#include "tse/fk.h"
#include "tse/ik.h"

/* kinematics.md: |q - q_exact| <= 2e-6 m in single precision wherever mu >= 0.1. */
#define SLIDE_TOL 2e-6
#define MU_ACCURATE 0.1f

/* FK: the float answer p_f is accepted by tse_fk only if the float IK of p_f reproduces the
 * given slides within verify_tol = 0.01 sqrt(FLT_EPSILON) L (fk.c; 5.96e-6 m for L = 1.727 m).
 * The float IK is itself within SLIDE_TOL of exact, and the slides handed over are the double
 * ones rounded to float (at most 0.5 ulp of 1 m = 6e-8 m off).  So the exact slides of p_f are
 * within FK_SLIDE_BOUND of the table's, and to first order each pose component is within
 * FK_SLIDE_BOUND * sum_j |(dq/dp)^-1_ij| of the table's pose: the generator records that sum
 * (fk_sens) from the double Jacobian at the pose.  An FK that converged to another assembly mode,
 * or stopped early, lands far outside it. */
#define FK_SLIDE_BOUND (0.01 * 3.4526698e-4 * 1.727 + SLIDE_TOL + 6e-8)

static tse_geometry geoms[KIN_DESIGNS];

static const char *const status_names[TSE_STATUS_COUNT] = {
    "ok", "invalid", "unreachable", "below", "alpha", "stroke", "singular", "degenerate", "noconverge"};

static long nm(double metres)
{
    return (long)(metres * 1e9 + (metres >= 0 ? 0.5 : -0.5));
}

static void designs(void)
{
    for (int d = 0; d < KIN_DESIGNS; ++d) {
        const kin_design *k = &kin_designs[d];
        const tse_params p = {k->L, k->k1, k->eta, k->k3, k->k4, k->alpha_min, k->alpha_max,
                              k->s_min, k->s_max, k->mu_min, k->nu_min};
        TT_CHECKF(tse_geometry_init(&geoms[d], &p) == TSE_PARAM_OK, "design %d refused\n", d);
    }
    unsigned n[TSE_STATUS_COUNT] = {0}, starts = 0, fk = 0;
    for (unsigned i = 0; i < kin_case_count; ++i) {
        TT_CHECK(kin_cases[i].status < TSE_STATUS_COUNT && kin_cases[i].design < KIN_DESIGNS);
        if (kin_cases[i].status < TSE_STATUS_COUNT)
            ++n[kin_cases[i].status];
        starts += kin_cases[i].path_start;
        fk += kin_cases[i].fk;
    }
    sh_printf("  %u poses in %u paths, %u with FK:", kin_case_count, starts, fk);
    for (int s = 0; s < TSE_STATUS_COUNT; ++s)
        sh_printf(" %s %u", status_names[s], n[s]);
    sh_printf("\n");
    /* Every status of the contract but noconverge is in the table. */
    for (int s = TSE_OK; s <= TSE_DEGENERATE; ++s)
        TT_CHECKF(n[s] > 0, "no pose of status %s\n", status_names[s]);
    TT_CHECK(n[TSE_NOCONVERGE] == 0);
    TT_CHECK(kin_cases[0].path_start == 1);
}

typedef struct {
    double worst;       /* m, over the slides checked against SLIDE_TOL */
    unsigned worst_case;
    double worst_weak;  /* m, slides of scissors with mu < 0.1 (reported, not bounded) */
    unsigned checked;
    unsigned status_bad;
} ik_stats;

static void check_case(unsigned i, const tse_ik_result *r, ik_stats *st, const char *pass)
{
    const kin_case *e = &kin_cases[i];
    const bool same = r->status == (tse_status)e->status && r->scissor == e->scissor;
    if (!same)
        ++st->status_bad;
    TT_CHECKF(same, "%s case %u: status %s scissor %d, double says %s scissor %d\n", pass, i,
              r->status < TSE_STATUS_COUNT ? status_names[r->status] : "?", r->scissor,
              status_names[e->status], e->scissor);
    for (int s = 0; s < 3; ++s) {
        for (int j = 2 * s; j < 2 * s + 2; ++j) {
            if (!isfinite(e->q[j]))
                continue;
            TT_CHECKF(isfinite(r->q[j]), "%s case %u: slide %d not solved\n", pass, i, j);
            if (!isfinite(r->q[j]))
                continue;
            const double err = fabs((double)r->q[j] - e->q[j]);
            if (e->mu[s] >= MU_ACCURATE) {
                ++st->checked;
                if (err > st->worst) {
                    st->worst = err;
                    st->worst_case = i;
                }
                TT_CHECKF(err <= SLIDE_TOL, "%s case %u slide %d: %ld nm from double (mu %ld ppm)\n", pass, i,
                          j, nm(err), (long)(e->mu[s] * 1e6f));
            } else if (err > st->worst_weak) {
                st->worst_weak = err;
            }
        }
    }
    if (e->status == TSE_OK)
        for (int j = 0; j < 6; ++j)
            TT_CHECK(isfinite(r->q[j]));
}

static void report(const char *pass, const ik_stats *st)
{
    sh_printf("  %s: %u slides checked, worst %ld nm (case %u, bound %ld nm); mu < 0.1: worst %ld nm\n", pass,
              st->checked, nm(st->worst), st->worst_case, nm(SLIDE_TOL), nm(st->worst_weak));
}

static void ik_cold(void)
{
    ik_stats st = {0};
    for (unsigned i = 0; i < kin_case_count; ++i) {
        const kin_case *e = &kin_cases[i];
        tse_ik_result r;
        tse_ik(&geoms[e->design], e->pose, NULL, &r);
        check_case(i, &r, &st, "cold");
    }
    report("cold", &st);
    TT_CHECK(st.checked > 100);
}

static bool all_finite(const tse_real q[6])
{
    for (int k = 0; k < 6; ++k)
        if (!isfinite(q[k]))
            return false;
    return true;
}

static void ik_warm(void)
{
    ik_stats st = {0};
    tse_real seed[6];
    bool have_seed = false;
    unsigned seeded = 0;
    for (unsigned i = 0; i < kin_case_count; ++i) {
        const kin_case *e = &kin_cases[i];
        if (e->path_start)
            have_seed = false;
        tse_ik_result r;
        tse_ik(&geoms[e->design], e->pose, have_seed ? seed : NULL, &r);
        seeded += have_seed;
        check_case(i, &r, &st, "warm");
        if (all_finite(r.q)) {
            memcpy(seed, r.q, sizeof seed);
            have_seed = true;
        }
    }
    report("warm", &st);
    sh_printf("  warm: %u of %u poses seeded\n", seeded, kin_case_count);
    TT_CHECK(seeded > kin_case_count / 2);
}

static void fk_from_home(void)
{
    unsigned checked = 0;
    double worst_ratio = 0.0, worst_pos = 0.0, worst_rot = 0.0;
    unsigned worst_case = 0;
    for (unsigned i = 0; i < kin_case_count; ++i) {
        const kin_case *e = &kin_cases[i];
        if (!e->fk || !(e->mu[0] >= MU_ACCURATE && e->mu[1] >= MU_ACCURATE && e->mu[2] >= MU_ACCURATE))
            continue;
        tse_real q[6];
        for (int k = 0; k < 6; ++k)
            q[k] = (tse_real)e->q[k];
        tse_fk_result f;
        tse_fk(&geoms[e->design], q, NULL, &f);
        ++checked;
        TT_CHECKF(f.status == TSE_OK, "FK case %u: status %s\n", i,
                  f.status < TSE_STATUS_COUNT ? status_names[f.status] : "?");
        if (f.status != TSE_OK)
            continue;
        for (int k = 0; k < 6; ++k) {
            const double err = fabs((double)f.pose[k] - (double)e->pose[k]);
            const double bound = FK_SLIDE_BOUND * (double)e->fk_sens[k];
            TT_CHECKF(err <= bound, "FK case %u component %d: %ld n(m|rad) off, bound %ld\n", i, k, nm(err),
                      nm(bound));
            const double ratio = err / bound;
            if (ratio > worst_ratio) {
                worst_ratio = ratio;
                worst_case = i;
            }
            if (k < 3 && err > worst_pos)
                worst_pos = err;
            if (k >= 3 && err > worst_rot)
                worst_rot = err;
        }
    }
    sh_printf("  FK: %u poses, worst %ld nm in position, %ld nrad in orientation; worst error / bound "
              "%ld ppm (case %u)\n",
              checked, nm(worst_pos), nm(worst_rot), (long)(worst_ratio * 1e6), worst_case);
    TT_CHECK(checked > 50);
}

int main(void)
{
    tt_begin("kinematics");
    tt_case("table and designs", designs);
    tt_case("IK cold: status, scissor, slides within 2 um of double", ik_cold);
    tt_case("IK warm along the paths", ik_warm);
    tt_case("FK from home returns the pose", fk_from_home);
    tt_finish();
}
