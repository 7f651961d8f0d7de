/* The move planner (fw/move.h: fw_move_plan) in float on the emulated Cortex-M4F, validating and
 * then executing moves the way the controller does: at every control segment's time (1 kHz), the
 * pose of the move, then the inverse kinematics warm from the previous segment's slides.
 *
 * Expectations come from outside the planner: the reference poses' slides and the failing paths
 * were computed on the host in double (gen_kin_table.c, kin_table.h); speeds and accelerations
 * are measured here from the executed slides, against the limits the planner was given.
 * - a reachable move is accepted, every segment solves, the executed pose stays on the straight
 *   line, the move ends on the commanded pose and its slides within 2 um (the float accuracy of
 *   kinematics.md) of the double ones, slide speed and acceleration within the limits;
 * - a move the slide limits cannot follow in the time asked is stretched: accepted, longer than
 *   the same move planned without slide limits, whose execution would break them, and the
 *   stretched one does not;
 * - a move through a region where the IK fails is rejected naming the first failing point: the
 *   status and scissor the double IK finds there, at a path position u just past where the double
 *   IK first fails, and the float IK of that point (its pose computed here) fails the same way.
 *
 * Measures: speed from one segment to the next; acceleration as the second difference over
 * S = 10 segments (10 ms), (q[k] - 2 q[k-S] + q[k-2S]) / (S T)^2, with the slides at rest before
 * and after the move.  Over one segment the float IK's rounding (about 1e-7 m) alone would read
 * 4e-7 / (1 ms)^2 = 0.4 m/s^2, 40 % of the default limit; over 10 ms it reads 0.004 m/s^2.  The
 * planner keeps 5 % of each limit in hand (move.c), which covers the smoothing of the peak
 * acceleration of its cycloidal ramps (>= 0.1 s long) by a 20 ms window (< 1 %). */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "fw/move.h"
#include "fw/validate.h"
#include "kin_table.h"
#include "target_test.h"
#include "tse/ik.h"

#define SEGMENT_HZ 1000.0f
#define SLIDE_TOL 2e-6 /* kinematics.md: float slides within 2e-6 m where mu >= 0.1 */
#define STRIDE 10

static tse_geometry geom;
static fw_limits board_lim;

static long nm(double m)
{
    return (long)(m * 1e9 + (m >= 0 ? 0.5 : -0.5));
}

static void ref_pose(int r, tse_real p[6])
{
    for (int k = 0; k < 6; ++k)
        p[k] = (tse_real)kin_refs[r].pose_u[k] * 1e-6f;
}

static void setup(void)
{
    const kin_design *k = &kin_designs[0];
    const tse_params p = {k->L,     k->k1,    k->eta,    k->k3,     k->k4,   k->alpha_min,
                          k->alpha_max, k->s_min, k->s_max, k->mu_min, k->nu_min};
    TT_CHECK(tse_geometry_init(&geom, &p) == TSE_PARAM_OK);
    /* The controller's limits at the parameter defaults (params.c, controller.c): slides 0.15 m/s
     * capped by 90 % of 199 steps a segment at 1.28M steps/m (0.1399 m/s), 1 m/s^2; plate 0.3 m/s,
     * 1 m/s^2, 10 m/s^3; 0.5 rad/s, 2 rad/s^2. */
    board_lim = (fw_limits){0.9f * 199.0f * SEGMENT_HZ / 1280000.0f, 1.0f, 0.3f, 1.0f, 10.0f, 0.5f, 2.0f, SEGMENT_HZ,
                            FW_LIMIT_STEP_GENERATOR};
}

typedef struct {
    double v_ratio, a_ratio; /* worst measured over the limits */
    double line_dev;         /* m: farthest executed position from the straight line */
    double end_err;          /* m: final slides against the double reference */
    unsigned segments, ik_fail;
    bool end_exact;          /* the last pose is the commanded one, bit for bit */
} run_stats;

/* Executes a planned move as the controller does and measures it against lim. */
static run_stats execute(const fw_move *mv, const fw_limits *lim, const tse_real q_from[6], const double *q_ref)
{
    run_stats st;
    memset(&st, 0, sizeof st);
    static tse_real ring[2 * STRIDE][6]; /* slot n % 2S: sample n - 2S until sample n replaces it */
    unsigned n = 0; /* samples fed to the ring */
    for (unsigned j = 0; j < 2 * STRIDE; ++j)
        memcpy(ring[j], q_from, sizeof ring[0]);
    tse_real q[6], prev[6];
    memcpy(q, q_from, sizeof q);
    float t_prev = 0.0f;
    const float span = (float)STRIDE / lim->segment_hz;
    tse_real pose[6];
    /* the straight line of the plate's centre */
    double d[3], len2 = 0.0;
    for (int k = 0; k < 3; ++k) {
        d[k] = (double)mv->to[k] - (double)mv->from[k];
        len2 += d[k] * d[k];
    }
    const unsigned total = mv->segments + 2 * STRIDE; /* then at rest */
    for (unsigned s = 1; s <= total; ++s) {
        memcpy(prev, q, sizeof prev);
        float t;
        if (s <= mv->segments) {
            t = fw_move_segment_time(mv, lim, s);
            fw_move_pose(mv, t, pose);
            tse_ik_result r;
            if (tse_ik(&geom, pose, q, &r) != TSE_OK) {
                ++st.ik_fail;
                continue;
            }
            memcpy(q, r.q, sizeof q);
            ++st.segments;
            /* distance of the centre from the line from -> to */
            double w[3], along = 0.0;
            for (int k = 0; k < 3; ++k) {
                w[k] = (double)pose[k] - (double)mv->from[k];
                along += w[k] * d[k];
            }
            double off = 0.0;
            for (int k = 0; k < 3; ++k) {
                const double c = w[k] - (len2 > 0.0 ? along / len2 : 0.0) * d[k];
                off += c * c;
            }
            if (sqrt(off) > st.line_dev)
                st.line_dev = sqrt(off);
            /* speed over this segment */
            const float dt = t - t_prev;
            for (int k = 0; k < 6; ++k) {
                const double v = dt > 0.0f ? fabs((double)(q[k] - prev[k])) / dt : 0.0;
                if (v / lim->slide_vmax > st.v_ratio)
                    st.v_ratio = v / lim->slide_vmax;
            }
            t_prev = t;
        }
        /* acceleration over the stride, on every sample (rest before and after included) */
        ++n;
        const tse_real *old2 = ring[n % (2 * STRIDE)];
        const tse_real *old1 = ring[(n + STRIDE) % (2 * STRIDE)];
        for (int k = 0; k < 6; ++k) {
            const double a = ((double)q[k] - 2.0 * (double)old1[k] + (double)old2[k]) / ((double)span * span);
            if (fabs(a) / lim->slide_amax > st.a_ratio)
                st.a_ratio = fabs(a) / lim->slide_amax;
        }
        memcpy(ring[n % (2 * STRIDE)], q, sizeof ring[0]);
    }
    st.end_exact = memcmp(pose, mv->to, sizeof pose) == 0;
    if (q_ref)
        for (int k = 0; k < 6; ++k)
            if (fabs((double)q[k] - q_ref[k]) > st.end_err)
                st.end_err = fabs((double)q[k] - q_ref[k]);
    return st;
}

static bool start_slides(const tse_real from[6], tse_real q[6])
{
    tse_ik_result r;
    const bool ok = tse_ik(&geom, from, NULL, &r) == TSE_OK;
    memcpy(q, r.q, sizeof r.q);
    return ok;
}

static void report(const char *name, const fw_move *mv, const run_stats *st)
{
    sh_printf("  %s: %lu segments, T %ld ms, stretch %ld/1000; peak slide speed %ld/1000 and "
              "acceleration %ld/1000 of the limits; off the line %ld nm; end %ld nm from double\n",
              name, (unsigned long)mv->segments, (long)(mv->prof.T * 1000.0f + 0.5f),
              (long)(mv->stretch * 1000.0f + 0.5f), (long)(st->v_ratio * 1000.0), (long)(st->a_ratio * 1000.0),
              nm(st->line_dev), nm(st->end_err));
}

static void reachable_moves(void)
{
    setup();
    static const struct {
        int from, to;
        fw_move_kind kind;
        float value;
        const char *name;
    } moves[] = {
        {REF_START, REF_NEAR, FW_MOVE_DURATION, 1.5f, "start -> near, 1.5 s"},
        {REF_START, REF_FAR, FW_MOVE_SPEED, 0.1f, "start -> far, 0.1 m/s"},
        {REF_START, REF_TURN, FW_MOVE_SPEED, 0.2f, "start -> turn (rotation only), at the angular limit"},
        {REF_FAR, REF_NEAR, FW_MOVE_DURATION, 0.2f, "far -> near, 0.2 s asked"},
    };
    for (unsigned i = 0; i < sizeof moves / sizeof moves[0]; ++i) {
        tse_real from[6], to[6], q0[6];
        ref_pose(moves[i].from, from);
        ref_pose(moves[i].to, to);
        TT_CHECK(start_slides(from, q0));
        static fw_move mv;
        fw_plan_result res;
        const int rc = fw_move_plan(&mv, &geom, &board_lim, from, to, moves[i].kind, moves[i].value, q0, &res);
        TT_CHECKF(rc == 0 && res.reason == FW_REASON_NONE, "%s: refused (reason %d, status %d)\n", moves[i].name,
                  (int)res.reason, (int)res.status);
        if (rc != 0)
            continue;
        const run_stats st = execute(&mv, &board_lim, q0, kin_refs[moves[i].to].q);
        report(moves[i].name, &mv, &st);
        TT_CHECK(st.ik_fail == 0 && st.segments == mv.segments);
        TT_CHECK(st.end_exact);
        TT_CHECKF(st.end_err <= SLIDE_TOL, "%s: end %ld nm from the double slides\n", moves[i].name, nm(st.end_err));
        TT_CHECK(st.line_dev <= 1e-6);
        TT_CHECK(st.v_ratio <= 1.0);
        TT_CHECK(st.a_ratio <= 1.0);
        /* the segments cover the move, the last one ending exactly at its end */
        TT_CHECK(mv.segments == (uint32_t)ceilf(mv.prof.T * SEGMENT_HZ));
        TT_CHECK(fw_move_segment_time(&mv, &board_lim, mv.segments) == mv.prof.T);
        if (moves[i].kind == FW_MOVE_DURATION) {
            TT_CHECK(mv.prof.T >= moves[i].value * (1.0f - 1e-6f));
            if (mv.stretch == 1.0f && i == 0)
                TT_CHECK(fabsf(mv.prof.T - moves[i].value) <= 1e-4f); /* what was asked, no more */
        }
    }
}

/* Slower slides than the board's, so that an ordinary move must be slowed down. */
static void too_fast_is_stretched(void)
{
    setup();
    fw_limits slow = board_lim;
    slow.slide_vmax = 0.03f;
    slow.slide_amax = 0.2f;
    fw_limits free_lim = board_lim;
    free_lim.slide_vmax = 100.0f;
    free_lim.slide_amax = 1000.0f;
    tse_real from[6], to[6], q0[6];
    ref_pose(REF_START, from);
    ref_pose(REF_NEAR, to);
    TT_CHECK(start_slides(from, q0));
    static fw_move fast, mv;
    fw_plan_result res;
    TT_CHECK(fw_move_plan(&fast, &geom, &free_lim, from, to, FW_MOVE_DURATION, 0.3f, q0, &res) == 0);
    TT_CHECK(fw_move_plan(&mv, &geom, &slow, from, to, FW_MOVE_DURATION, 0.3f, q0, &res) == 0);
    TT_CHECK(res.reason == FW_REASON_NONE);
    /* the unstretched timing breaks the slow limits; the planner's does not */
    const run_stats sf = execute(&fast, &slow, q0, kin_refs[REF_NEAR].q);
    const run_stats st = execute(&mv, &slow, q0, kin_refs[REF_NEAR].q);
    report("start -> near, 0.3 s, no slide limit", &fast, &sf);
    report("the same under 0.03 m/s, 0.2 m/s^2", &mv, &st);
    TT_CHECK(sf.v_ratio > 1.0 || sf.a_ratio > 1.0);
    TT_CHECK(mv.prof.T > 1.05f * fast.prof.T);
    TT_CHECK(mv.stretch > 1.0f);
    TT_CHECK(st.ik_fail == 0 && st.end_exact && st.end_err <= SLIDE_TOL);
    TT_CHECK(st.v_ratio <= 1.0 && st.a_ratio <= 1.0);
    /* not slower than it needs: the worst limit is used to at least 80 % */
    TT_CHECK(st.v_ratio > 0.8 || st.a_ratio > 0.8);
}

static void unreachable_path_rejected(void)
{
    setup();
    TT_CHECK(kin_path_count >= 2);
    for (unsigned i = 0; i < kin_path_count; ++i) {
        const kin_path *kp = &kin_paths[i];
        tse_real q0[6];
        TT_CHECK(start_slides(kp->from, q0));
        /* both ends are accepted: only the whole path shows the problem */
        tse_real q1[6];
        TT_CHECK(start_slides(kp->to, q1));
        static fw_move mv;
        fw_plan_result res;
        const int rc = fw_move_plan(&mv, &geom, &board_lim, kp->from, kp->to, FW_MOVE_DURATION, 2.0f, q0, &res);
        TT_CHECK(rc != 0);
        TT_CHECK(res.reason == FW_REASON_KINEMATICS);
        TT_CHECKF(res.status == (tse_status)kp->status && res.scissor == kp->scissor,
                  "path %u: status %d scissor %d, double says %d on %d\n", i, (int)res.status, res.scissor,
                  kp->status, kp->scissor);
        /* The first failing segment is the first after the boundary: u within one segment's
         * advance past it (at most plate_vmax / |path| / 1 kHz <= 0.0006 here), and float may
         * place the boundary a hair away from double. */
        const double where = res.where;
        TT_CHECKF(where >= kp->u_first - 1e-5 && where <= kp->u_first + 1e-3,
                  "path %u: first failing u %ld ppm, double boundary %ld ppm\n", i, (long)(where * 1e6),
                  (long)(kp->u_first * 1e6));
        TT_CHECK(res.segment >= 1 && res.segment < mv.segments);
        /* that point, computed here, fails in float the same way */
        tse_real p[6];
        for (int k = 0; k < 6; ++k)
            p[k] = k < 3 ? kp->from[k] + res.where * (kp->to[k] - kp->from[k]) : kp->from[k];
        tse_ik_result r;
        tse_ik(&geom, p, NULL, &r);
        TT_CHECK(r.status == (tse_status)kp->status && r.scissor == kp->scissor);
        sh_printf("  path %u: rejected at segment %lu of %lu, u = %ld ppm (double boundary %ld ppm), status %d on "
                  "scissor %d\n",
                  i, (unsigned long)res.segment, (unsigned long)mv.segments, (long)(where * 1e6),
                  (long)(kp->u_first * 1e6), (int)res.status, res.scissor);
    }
}

static void bad_requests(void)
{
    setup();
    tse_real from[6], to[6], q0[6];
    ref_pose(REF_START, from);
    ref_pose(REF_NEAR, to);
    TT_CHECK(start_slides(from, q0));
    static fw_move mv;
    fw_plan_result res;
    TT_CHECK(fw_move_plan(&mv, &geom, &board_lim, from, to, FW_MOVE_DURATION, 0.0f, q0, &res) != 0);
    TT_CHECK(res.reason == FW_REASON_RANGE);
    to[2] = NAN;
    TT_CHECK(fw_move_plan(&mv, &geom, &board_lim, from, to, FW_MOVE_SPEED, 0.1f, q0, &res) != 0);
    TT_CHECK(res.reason == FW_REASON_RANGE);
}

/* The piecewise proof (fw/validate.h) against the per-segment walk in the board's float, on moves
 * from the start pose to just inside or just outside the workspace boundary along random
 * directions (found by bisection with the float IK): the same verdict, a refusal at the same
 * segment, status and scissor; our accepted plan, walked segment by segment, within the limits
 * aimed at (95 %) up to the float rounding the walk reads. */
static uint32_t lcg = 12345u;

static float unit(void)
{
    lcg = lcg * 1664525u + 1013904223u;
    return (float)(lcg >> 8) * (1.0f / 16777216.0f);
}

static void proof_matches_walk(void)
{
    setup();
    tse_real from[6], q0[6];
    ref_pose(REF_START, from);
    TT_CHECK(start_slides(from, q0));
    static fw_move fast, walk;
    int refused = 0, accepted = 0;
    unsigned pieces = 0, solves = 0, segments = 0;
    for (int n = 0; n < 24; ++n) {
        tse_real dir[6], to[6];
        for (int k = 0; k < 6; ++k)
            dir[k] = (unit() - 0.5f) * (k < 2 ? 0.5f : k == 2 ? 1.2f : 0.6f);
        float lo = 0.0f, hi = 1.0f;
        for (int it = 0; it < 24; ++it) {
            const float mid = 0.5f * (lo + hi);
            for (int k = 0; k < 6; ++k)
                to[k] = from[k] + mid * dir[k];
            tse_ik_result r;
            if (tse_ik(&geom, to, NULL, &r) == TSE_OK)
                lo = mid;
            else
                hi = mid;
        }
        const float t = lo * (1.0f + (unit() - 0.3f) * 0.04f);
        for (int k = 0; k < 6; ++k)
            to[k] = from[k] + t * dir[k];
        const float dur = n % 3 == 0 ? 0.3f : 2.0f;
        fw_plan_result rf, rw;
        const int a = fw_move_plan_by(&fast, &geom, &board_lim, from, to, FW_MOVE_DURATION, dur, q0, &rf, fw_validate);
        const int b = fw_move_plan_by(&walk, &geom, &board_lim, from, to, FW_MOVE_DURATION, dur, q0, &rw,
                                      fw_validate_per_segment);
        TT_CHECK(a == b);
        if (b != 0) {
            ++refused;
            TT_CHECK(rf.reason == rw.reason && rf.segment == rw.segment && rf.status == rw.status &&
                     rf.scissor == rw.scissor);
            continue;
        }
        ++accepted;
        TT_CHECK(fast.stretch <= walk.stretch * 1.06f);
        fw_validation vf;
        TT_CHECK(fw_validate(&fast, &geom, &board_lim, q0, &vf, &rw) == 0);
        pieces += vf.pieces;
        solves += vf.solves;
        segments += fast.segments;
        fw_limits aim = board_lim;
        aim.slide_vmax *= 0.95f;
        aim.slide_amax *= 0.95f;
        fw_validation vw;
        fw_plan_result rr;
        TT_CHECK(fw_validate_per_segment(&fast, &geom, &aim, q0, &vw, &rr) == 0);
        /* float rounding read over 10 ms: 4e-7 m / (10 ms)^2 = 0.004 m/s^2, 0.4 % of the limit */
        TT_CHECK(vw.v_ratio <= 1.0f + 1e-3f && vw.a_ratio <= 1.0f + 1e-2f);
    }
    sh_printf("  %d moves refused, %d accepted: %u segments validated with %u solves in %u pieces\n", refused,
              accepted, segments, solves, pieces);
    TT_CHECK(refused >= 3 && accepted >= 3);
}

int main(void)
{
    tt_begin("planner");
    tt_case("reachable moves: accepted, executed within the limits, end on the double slides", reachable_moves);
    tt_case("a move too fast for the slides is stretched", too_fast_is_stretched);
    tt_case("a path through a failing region is rejected at its first failing point", unreachable_path_rejected);
    tt_case("malformed requests", bad_requests);
    tt_case("the piecewise proof gives the per-segment walk's verdict", proof_matches_walk);
    tt_finish();
}
