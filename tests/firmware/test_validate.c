/* Path validation (fw/validate.h): the piecewise proof against the per-segment walk, on random
 * moves grazing every limit: the workspace boundary (alpha stops), the stroke, the type-1 and the
 * type-2 margins (designs where each binds), and the slide speed and acceleration limits
 * (durations short enough to need stretching).  The per-segment walk is the reference:
 * - a move it refuses is refused, at the same segment with the same status and scissor;
 * - a move it accepts is accepted (the proof never refuses what the per-segment check takes);
 * - the plan accepted, walked segment by segment, keeps every slide within the limits the planner
 *   aims at (with its margin), and is stretched at most a few per cent more than the walk's plan.
 * The figures (pieces and solves against segments) are printed. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include <cmocka.h>

#include "fw/move.h"
#include "fw/validate.h"

static const fw_limits LIM = {0.2, 1.0, 0.3, 1.0, 10.0, 0.5, 2.0, 1000.0, FW_LIMIT_SLIDE_VMAX};

/* splitmix64 */
static uint64_t next(uint64_t *s)
{
    uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

static double uniform(uint64_t *s, double lo, double hi)
{
    return lo + (hi - lo) * (double)(next(s) >> 11) * (1.0 / 9007199254740992.0);
}

typedef struct {
    long moves, refused, accepted, stretched, fallbacks;
    double segments, solves, pieces;
    double worst_stretch;  /* largest stretch of ours over the walk's */
    double worst_ratio;    /* largest ratio the walk measures on our plan (1 = the planner's aim) */
} counts;

/* The largest t along dir from p0 that the inverse kinematics still accepts. */
static double boundary(const tse_geometry *g, const double p0[6], const double dir[6])
{
    double lo = 0.0, hi = 1.0;
    for (int it = 0; it < 40; ++it) {
        const double mid = 0.5 * (lo + hi);
        double p[6];
        for (int k = 0; k < 6; ++k)
            p[k] = p0[k] + mid * dir[k];
        tse_ik_result r;
        if (tse_ik(g, p, NULL, &r) == TSE_OK)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

static void compare(const tse_geometry *g, const double from[6], const double to[6], fw_move_kind kind,
                    double value, counts *c)
{
    tse_ik_result r0;
    if (tse_ik(g, from, NULL, &r0) != TSE_OK)
        return;
    static fw_move fast, walk;
    fw_plan_result rf, rw;
    const int a = fw_move_plan_by(&fast, g, &LIM, from, to, kind, value, r0.q, &rf, fw_validate);
    const int b = fw_move_plan_by(&walk, g, &LIM, from, to, kind, value, r0.q, &rw, fw_validate_per_segment);
    ++c->moves;
    if (b != 0) {
        ++c->refused;
        if (a == 0)
            fail_msg("the walk refuses (reason %d, status %d, segment %u) a move the proof accepts", rw.reason,
                     rw.status, rw.segment);
        assert_int_equal(rf.reason, rw.reason);
        if (rw.reason == FW_REASON_KINEMATICS) {
            if (rf.segment != rw.segment || rf.status != rw.status || rf.scissor != rw.scissor)
                fail_msg("refused at segment %u (status %d, scissor %d), the walk at %u (status %d, scissor %d)",
                         rf.segment, rf.status, rf.scissor, rw.segment, rw.status, rw.scissor);
        }
        return;
    }
    if (a != 0)
        fail_msg("the proof refuses (reason %d, status %d, segment %u of %u) a move the walk accepts", rf.reason,
                 rf.status, rf.segment, walk.segments);
    ++c->accepted;
    c->stretched += walk.stretch > 1.0;
    const double ratio = fast.stretch / walk.stretch;
    if (ratio > 1.06 && getenv("VDBG"))
        printf("stretch %.4f vs %.4f, T %.3f vs %.3f, kind %d value %g from %g %g %g %g %g %g to %g %g %g %g %g %g\n", fast.stretch, walk.stretch, fast.prof.T, walk.prof.T, kind, value, from[0], from[1], from[2], from[3], from[4], from[5], to[0], to[1], to[2], to[3], to[4], to[5]);
    if (ratio > c->worst_stretch)
        c->worst_stretch = ratio;
    /* Our plan, walked segment by segment at the planner's aim (95 % of the limits). */
    fw_limits aim = LIM;
    aim.slide_vmax *= 0.95;
    aim.slide_amax *= 0.95;
    fw_validation vw, vf;
    fw_plan_result rr;
    assert_int_equal(fw_validate_per_segment(&fast, g, &aim, r0.q, &vw, &rr), 0);
    const double worst = fmax(vw.v_ratio, vw.a_ratio);
    if (worst > c->worst_ratio)
        c->worst_ratio = worst;
    if (worst > 1.0 + 1e-9)
        fail_msg("our plan walked: speed %g, acceleration %g of the limits aimed at", vw.v_ratio, vw.a_ratio);
    /* The end slides agree with the walk's. */
    for (int k = 0; k < 6; ++k)
        assert_true(fabs(fast.q_end[k] - vw.q_end[k]) < 1e-9);
    assert_int_equal(fw_validate(&fast, g, &aim, r0.q, &vf, &rr), 0);
    c->fallbacks += vf.per_segment;
    c->segments += fast.segments;
    c->solves += vf.solves;
    c->pieces += vf.pieces;
}

/* Moves through a point on the boundary: along a random direction from home to just inside or
 * just outside it, and across it (tangent-ish, through a point just inside or outside). */
static void run_design(const tse_params *p, uint64_t seed, int n, counts *c)
{
    tse_geometry g;
    assert_int_equal(tse_geometry_init(&g, p), TSE_PARAM_OK);
    uint64_t rng = seed;
    static const double durations[] = {0.4, 1.0, 2.0, 5.0};
    for (int i = 0; i < n; ++i) {
        double dir[6] = {uniform(&rng, -0.3, 0.3), uniform(&rng, -0.3, 0.3), uniform(&rng, -0.7, 0.7),
                         uniform(&rng, -0.3, 0.3), uniform(&rng, -0.3, 0.3), uniform(&rng, -0.6, 0.6)};
        const double t = boundary(&g, g.home_pose, dir) * (1.0 + uniform(&rng, -0.004, 0.004));
        double edge[6], from[6], to[6];
        for (int k = 0; k < 6; ++k)
            edge[k] = g.home_pose[k] + t * dir[k];
        const double dur = durations[next(&rng) % 4];
        const fw_move_kind kind = next(&rng) % 5 == 0 ? FW_MOVE_SPEED : FW_MOVE_DURATION;
        const double value = kind == FW_MOVE_SPEED ? uniform(&rng, 0.02, 0.3) : dur;
        if (i % 2 == 0) {
            compare(&g, g.home_pose, edge, kind, value, c);
            continue;
        }
        /* Across: a chord through the edge point, from an inside pose. */
        const double w = uniform(&rng, 0.02, 0.1);
        for (int k = 0; k < 6; ++k) {
            const double d = uniform(&rng, -1, 1) * (k < 3 ? w : 2 * w);
            from[k] = edge[k] - d - 0.05 * t * dir[k];
            to[k] = edge[k] + d - 0.05 * t * dir[k];
        }
        /* ... bent back so that the chord's middle is the edge point itself */
        for (int k = 0; k < 6; ++k) {
            const double mid = 0.5 * (from[k] + to[k]);
            from[k] += edge[k] - mid;
            to[k] += edge[k] - mid;
        }
        compare(&g, from, to, kind, value, c);
    }
}

static void report(const char *name, const counts *c)
{
    printf("%s: %ld moves, %ld refused, %ld accepted (%ld stretched), %ld fell back to the walk; "
           "%.0f segments, %.0f solves (%.1f%%), %.0f pieces; stretch at most %.4f x the walk's; "
           "the walk on our plans: at most %.4f of the aim\n",
           name, c->moves, c->refused, c->accepted, c->stretched, c->fallbacks, c->segments, c->solves,
           100.0 * c->solves / (c->segments > 0 ? c->segments : 1), c->pieces, c->worst_stretch, c->worst_ratio);
}

static void check(const char *name, tse_params *p, uint64_t seed)
{
    counts c = {0};
    run_design(p, seed, 60, &c);
    report(name, &c);
    /* Not vacuous: both verdicts met, stretching met, and the proof not walking every move. */
    assert_true(c.refused >= 5);
    assert_true(c.accepted >= 5);
    assert_true(c.solves < 0.2 * c.segments);
    assert_true(c.worst_stretch < 1.06);
}

static void test_alpha_stops(void **state)
{
    (void)state;
    tse_params p;
    tse_params_default(&p);
    check("default design", &p, 11);
}

static void test_stroke(void **state)
{
    (void)state;
    tse_params p;
    tse_params_default(&p);
    p.s_max = 0.55;
    check("stroke 0.55 m", &p, 12);
}

static void test_type1(void **state)
{
    (void)state;
    tse_params p;
    tse_params_default(&p);
    p.mu_min = 0.6;
    check("mu_min 0.6", &p, 13);
}

static void test_type2(void **state)
{
    (void)state;
    tse_params p;
    tse_params_default(&p);
    p.nu_min = 0.5;
    check("nu_min 0.5", &p, 14);
}

/* Slides that start off the start pose's solution: the first segment's jump is measured as the
 * walk measures it (the proof's start gap). */
static void test_start_gap(void **state)
{
    (void)state;
    tse_params p;
    tse_params_default(&p);
    tse_geometry g;
    assert_int_equal(tse_geometry_init(&g, &p), TSE_PARAM_OK);
    const double to[6] = {0.05, -0.02, 1.1, 0.02, 0, 0.05};
    tse_ik_result r0;
    assert_int_equal(tse_ik(&g, g.home_pose, NULL, &r0), TSE_OK);
    fw_move mv;
    fw_plan_result res;
    assert_int_equal(fw_move_plan(&mv, &g, &LIM, g.home_pose, to, FW_MOVE_DURATION, 10.0, r0.q, &res), 0);
    for (int k = 0; k < 6; ++k) {
        double q[6];
        for (int j = 0; j < 6; ++j)
            q[j] = r0.q[j];
        q[k] += 1e-4 * (k + 1);
        fw_validation a, b;
        assert_int_equal(fw_validate(&mv, &g, &LIM, q, &a, &res), 0);
        assert_int_equal(fw_validate_per_segment(&mv, &g, &LIM, q, &b, &res), 0);
        assert_false(a.per_segment);
        /* the jump dominates the first segment: both see 1e-4 (k+1) m in 1 ms */
        assert_true(a.v_ratio >= b.v_ratio);
        assert_true(a.v_ratio < b.v_ratio * 1.001);
        assert_int_equal(a.worst.slide, b.worst.slide);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_start_gap),
        cmocka_unit_test(test_alpha_stops),
        cmocka_unit_test(test_stroke),
        cmocka_unit_test(test_type1),
        cmocka_unit_test(test_type2),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
