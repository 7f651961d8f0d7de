#include "fw/validate.h"

#include "fw/work.h"
#include "tse/enclose.h"

static void copy6(tse_real dst[6], const tse_real src[6])
{
    for (int k = 0; k < 6; ++k)
        dst[k] = src[k];
}

/* A KINEMATICS refusal at segment `segment` (ending at t), for status and scissor. */
static void refuse_at(const fw_move *mv, tse_real t, uint32_t segment, tse_status status, int scissor,
                      fw_plan_result *res)
{
    tse_real u, du, ddu;
    fw_profile_eval(&mv->prof, t, &u, &du, &ddu);
    res->reason = FW_REASON_KINEMATICS;
    res->status = status;
    res->scissor = scissor;
    res->segment = segment;
    res->where = u;
}

static void refuse(const fw_move *mv, tse_real t, uint32_t segment, const tse_ik_result *r, fw_plan_result *res)
{
    refuse_at(mv, t, segment, r->status, r->scissor, res);
}

int fw_validate_per_segment(const fw_move *mv, const tse_geometry *g, const fw_limits *lim,
                            const tse_real q_from[6], fw_validation *v, fw_plan_result *res)
{
    fw_slide_check chk;
    fw_slide_check_start(&chk, lim->slide_vmax, lim->slide_amax, lim->segment_hz, q_from);
    v->pieces = 0;
    v->solves = 0;
    v->per_segment = true;
    v->unproven = false;
    tse_real t_prev = TSE_R(0.0);
    for (uint32_t s = 1; s <= mv->segments; ++s) {
        if (fw_work_point()) {
            res->reason = FW_REASON_STATE; /* stopped from outside (fw/work.h) */
            return -1;
        }
        const tse_real t = fw_move_segment_time(mv, lim, s);
        tse_real pose[6];
        fw_move_pose(mv, t, pose);
        tse_ik_result r;
        ++v->solves;
        if (tse_ik(g, pose, chk.q, &r) != TSE_OK) {
            refuse(mv, t, s, &r, res);
            return -1;
        }
        fw_slide_check_feed(&chk, r.q, t - t_prev);
        t_prev = t;
    }
    fw_slide_check_finish(&chk);
    v->v_ratio = chk.v_ratio;
    v->a_ratio = chk.a_ratio;
    v->v_slide = chk.v_slide;
    v->a_slide = chk.a_slide;
    v->worst = fw_slide_check_worst(&chk);
    copy6(v->q_end, chk.q);
    return 0;
}

/* Whether every slide of q lies in the enclosure's box. */
static bool in_box(const tse_enclosure *e, const tse_real q[6])
{
    for (int k = 0; k < 6; ++k)
        if (!(q[k] >= e->q_lo[k] && q[k] <= e->q_hi[k]))
            return false;
    return true;
}

/* Successes in a row at one piece length before the next piece is tried at twice it. */
#define GROW_AFTER 3u
/* Pieces between two looks ahead for a failing segment (scan_ahead) while pieces fail checks. */
#define SCAN_EVERY 16u
/* The proof's work once the move is known to be refused (its end pose, or a segment ahead, fails):
 * the proof only places the first failure, which bisection then finds from where it stopped. */
#define REFUSAL_WORK (32u * FW_PIECE_WORK)

/* Relative slack allowed between a piece's timing bound and the largest speed or acceleration
 * actually met so far, before the piece is halved to tighten it. */
#define TIMING_SLACK TSE_R(0.02)

typedef struct {
    tse_real v[6], a[6];   /* each slide's worst bounds, as ratios to the limits */
    tse_real met_v, met_a; /* the largest ratios met at a piece's centre (lower bounds) */
} timing;

typedef struct {
    tse_real v[6], a[6];   /* the piece's bounds, as ratios */
    tse_real v_max, a_max; /* the largest of each */
} piece_timing;

/* Product of two intervals [lo, hi]. */
static void imul(const tse_real x[2], const tse_real y[2], tse_real out[2])
{
    const tse_real p[4] = {x[0] * y[0], x[0] * y[1], x[1] * y[0], x[1] * y[1]};
    out[0] = out[1] = p[0];
    for (int i = 1; i < 4; ++i) {
        if (p[i] < out[0])
            out[0] = p[i];
        if (p[i] > out[1])
            out[1] = p[i];
    }
}

/* The slides' speed and acceleration over a piece, in interval arithmetic from the enclosure's
 * derivatives along u (midpoint and radius) and the profile's speed and acceleration ranges over
 * the piece's time span: dq/dt = q' du/dt, d2q/dt2 = q'' (du/dt)^2 + q' d2u/dt2, whose two terms
 * often cancel (a slide whose q' grows as the path slows down), which signed ranges keep.  Also the
 * values at the centre time, which the path does reach. */
static piece_timing piece_bounds(timing *tm, const tse_enclosure *e, const fw_move *mv, const fw_limits *lim,
                                 tse_real t0, tse_real t1, tse_real ud_c, tse_real udd_c)
{
    tse_real ud[2], udd[2];
    fw_profile_range(&mv->prof, t0, t1, ud, udd);
    const tse_real ud_hi = tse_fabs(ud[0]) > tse_fabs(ud[1]) ? tse_fabs(ud[0]) : tse_fabs(ud[1]);
    const tse_real ud_lo = ud[0] > TSE_R(0.0) ? ud[0] : TSE_R(0.0);
    const tse_real ud2[2] = {ud_lo * ud_lo, ud_hi * ud_hi};
    piece_timing pt;
    pt.v_max = TSE_R(0.0);
    pt.a_max = TSE_R(0.0);
    for (int k = 0; k < 6; ++k) {
        const tse_real r1 = e->dq[k] - tse_fabs(e->dq_c[k]), r2 = e->ddq[k] - tse_fabs(e->ddq_c[k]);
        const tse_real q1[2] = {e->dq_c[k] - r1, e->dq_c[k] + r1};
        const tse_real q2[2] = {e->ddq_c[k] - r2, e->ddq_c[k] + r2};
        tse_real t2[2], t1r[2];
        imul(q2, ud2, t2);
        imul(q1, udd, t1r);
        const tse_real lo = t2[0] + t1r[0], hi = t2[1] + t1r[1];
        pt.v[k] = e->dq[k] * ud_hi / lim->slide_vmax;
        pt.a[k] = (tse_fabs(lo) > tse_fabs(hi) ? tse_fabs(lo) : tse_fabs(hi)) / lim->slide_amax;
        if (pt.v[k] > pt.v_max)
            pt.v_max = pt.v[k];
        if (pt.a[k] > pt.a_max)
            pt.a_max = pt.a[k];
        const tse_real mv_k = tse_fabs(e->dq_c[k] * ud_c) / lim->slide_vmax;
        const tse_real ma_k = tse_fabs(e->ddq_c[k] * ud_c * ud_c + e->dq_c[k] * udd_c) / lim->slide_amax;
        if (mv_k > tm->met_v)
            tm->met_v = mv_k;
        if (ma_k > tm->met_a)
            tm->met_a = ma_k;
    }
    return pt;
}

/* A piece whose bound is over the limit but well above what the path is seen to need would
 * stretch the move for the bound's slack alone: it is halved until its bound is close. */
static bool too_loose(const timing *tm, const piece_timing *pt)
{
    return (pt->v_max > TSE_R(1.0) && pt->v_max > tm->met_v * (TSE_R(1.0) + TIMING_SLACK)) ||
           (pt->a_max > TSE_R(1.0) && pt->a_max > tm->met_a * (TSE_R(1.0) + TIMING_SLACK));
}

static void account(timing *tm, const piece_timing *pt)
{
    for (int k = 0; k < 6; ++k) {
        if (pt->v[k] > tm->v[k])
            tm->v[k] = pt->v[k];
        if (pt->a[k] > tm->a[k])
            tm->a[k] = pt->a[k];
    }
}

/* The box of a piece, all that the next piece needs of it. */
typedef struct {
    tse_real lo[6], hi[6];
} box6;

static void keep_box(box6 *b, const tse_enclosure *e)
{
    copy6(b->lo, e->q_lo);
    copy6(b->hi, e->q_hi);
}

static bool box_holds(const box6 *b, const tse_real q[6])
{
    for (int k = 0; k < 6; ++k)
        if (!(q[k] >= b->lo[k] && q[k] <= b->hi[k]))
            return false;
    return true;
}

/* Whether two boxes overlap in every slide: the same branch passes from one piece to the next.
 * Two solutions of one scissor for one ball joint lie a scissor's size apart, boxes micrometres
 * to millimetres wide: overlapping boxes hold the same one. */
static bool boxes_meet(const box6 *a, const tse_enclosure *b)
{
    for (int k = 0; k < 6; ++k)
        if (!(a->lo[k] <= b->q_hi[k] && b->q_lo[k] <= a->hi[k]))
            return false;
    return true;
}

/* Where a proof stopped short of a verdict (prove returns 1), for settle(). */
typedef struct {
    uint32_t at;          /* the last segment reached along the branch: passes (0: the start) */
    tse_real q[6];        /* slides on the branch there, or near it: a seed for what lies ahead */
    tse_status why;       /* what the proof could not get past (the enclosure's status) */
    int why_scissor;
    uint32_t fail;        /* a later segment known to fail (0: none known) */
    tse_status fail_status;
    int fail_scissor;
    uint32_t fail_from;   /* a segment before it that passes, at or after `at` once stalled, */
    tse_real fail_q[6];   /* with its slides: where bisection starts */
} stall;

static void stall_at(stall *st, uint32_t at, const tse_real q[6], tse_status why, int scissor)
{
    st->at = at;
    copy6(st->q, q);
    st->why = why;
    st->why_scissor = scissor;
}

/* Segments lo + 1, lo + 3, lo + 7, ... before the end, each solved from the one before as the walk
 * would (from q, slides on the branch at lo): the first that fails goes into st->fail (true).  A
 * proof slows down near a limit, so a failure, if the path has one there, is close ahead. */
static bool scan_ahead(const fw_move *mv, const tse_geometry *g, const fw_limits *lim, uint32_t lo,
                       const tse_real q[6], stall *st, fw_validation *v)
{
    tse_real seed[6];
    copy6(seed, q);
    for (uint32_t d = 1u; lo + d < mv->segments; d *= 2u) {
        tse_real pose[6];
        tse_ik_result r;
        fw_move_pose(mv, fw_move_segment_time(mv, lim, lo + d), pose);
        ++v->solves;
        if (tse_ik(g, pose, seed, &r) != TSE_OK) {
            st->fail = lo + d;
            st->fail_status = r.status;
            st->fail_scissor = r.scissor;
            st->fail_from = lo;
            copy6(st->fail_q, seed);
            return true;
        }
        lo += d;
        copy6(seed, r.q);
    }
    return false;
}

/* Returns 0 (valid), -1 (refused, *res filled) or 1 (stalled: *st says where; settle() decides).
 * Kept out of line so that the stack holds either this walk or the per-segment one, not both. */
static __attribute__((noinline)) int prove(const fw_move *mv, const tse_geometry *g, const fw_limits *lim,
                                           const tse_real q_from[6], fw_validation *v, fw_plan_result *res,
                                           stall *st)
{
    const uint32_t n = mv->segments;
    /* The poses' rounding, for the ball joints: a few units in the last place of the position and
     * the plate; and where the slerp falls back to a normalised lerp (half-angle below 1e-4), its
     * departure from a constant rate, of order angle^3. */
    tse_real extent = g->r_top;
    for (int k = 0; k < 3; ++k)
        extent += tse_fabs(mv->from[k]) + tse_fabs(mv->dp[k]);
    tse_real pad = TSE_R(64.0) * TSE_REAL_EPS * extent;
    if (mv->angle < TSE_R(2e-4))
        pad += g->r_top * mv->angle * mv->angle * mv->angle;
    const tse_real u_pad = TSE_R(4.0) * TSE_REAL_EPS;
    tse_piece piece;
    for (int k = 0; k < 3; ++k) {
        piece.lin[k] = mv->dp[k];
        piece.omega[k] = mv->omega[k];
    }
    piece.pad = pad;
    tse_real pose[6], q_start[6], q_first[6], seed[6];
    tse_ik_result r;
    v->solves = 3;
    v->pieces = 0;
    v->per_segment = false;
    v->unproven = false;
    stall_at(st, 0, q_from, TSE_SINGULAR, 1);
    st->fail = 0;

    /* The end pose first: one the solver refuses makes the move a refusal wherever the path first
     * fails, so the pieces need not be cut short for tight timing bounds, only for the proof. */
    fw_move_pose(mv, mv->prof.T, pose);
    bool refusing = tse_ik(g, pose, q_from, &r) != TSE_OK;
    if (refusing) {
        st->fail = n;
        st->fail_status = r.status;
        st->fail_scissor = r.scissor;
        st->fail_from = 0;
        copy6(st->fail_q, q_from);
    }

    /* The slides the move starts from may differ from the start pose's solution (by the solver's
     * rounding, or more): the per-segment walk sees that gap in its first setpoints, so it is
     * measured here as that walk measures it.  The first segment's speed is its setpoint's
     * distance from q_from; and setpoints before the start hold q_from, not the branch's start,
     * which moves every second difference over the first strides by at most the gap.  The first
     * segment is solved as the walk solves it, so a refusal there is the walk's. */
    const tse_real t_first = fw_move_segment_time(mv, lim, 1u);
    fw_move_pose(mv, t_first, pose);
    if (tse_ik(g, pose, q_from, &r) != TSE_OK) {
        refuse(mv, t_first, 1u, &r, res);
        return -1;
    }
    copy6(q_first, r.q);
    fw_move_pose(mv, TSE_R(0.0), pose);
    if (tse_ik(g, pose, q_from, &r) != TSE_OK) {
        stall_at(st, 1u, q_first, r.status, r.scissor);
        return 1;
    }
    copy6(q_start, r.q);
    copy6(seed, q_start);

    /* Pieces from the start to the end, each as long as can be proven: halved on a failure,
     * doubled after GROW_AFTER successes in a row (a length that has just failed is likely to fail
     * again soon: doubling after every success would spend every other try on it). */
    timing tm;
    for (int k = 0; k < 6; ++k)
        tm.v[k] = tm.a[k] = TSE_R(0.0);
    tm.met_v = tm.met_a = TSE_R(0.0);
    box6 prev;
    bool have_prev = false;
    uint32_t s0 = 0, len = n, streak = 0, scanned = 0, longest = 0;
    /* The proof's share of the work (fw_validation_work): a move short enough to walk keeps the
     * rest for its walk. */
    uint32_t budget = refusing                ? REFUSAL_WORK
                      : n <= FW_VALIDATE_WALK ? FW_VALIDATE_WORK - FW_VALIDATE_WALK
                                              : FW_VALIDATE_WORK;
    while (s0 < n) {
        if (fw_work_point()) {
            res->reason = FW_REASON_STATE; /* stopped from outside (fw/work.h) */
            return -1;
        }
        if (fw_validation_work(v) >= budget) {
            st->at = s0;
            copy6(st->q, seed); /* the last piece's centre, on the branch that passes at s0 */
            return 1;
        }
        const uint32_t s1 = n - s0 > len ? s0 + len : n;
        const tse_real t0 = fw_move_segment_time(mv, lim, s0), t1 = fw_move_segment_time(mv, lim, s1);
        const tse_real tc = TSE_R(0.5) * (t0 + t1);
        tse_real u0, u1, uc, ud_c, udd_c, du, ddu;
        fw_profile_eval(&mv->prof, t0, &u0, &du, &ddu);
        fw_profile_eval(&mv->prof, t1, &u1, &du, &ddu);
        fw_profile_eval(&mv->prof, tc, &uc, &ud_c, &udd_c);
        piece.half = (uc - u0 > u1 - uc ? uc - u0 : u1 - uc) + u_pad;
        fw_move_pose_at(mv, uc, pose);
        tse_enclosure e;
        ++v->pieces;
        ++v->solves;
        const bool solved = tse_ik(g, pose, seed, &r) == TSE_OK;
        bool proven = solved && tse_ik_enclose(g, &piece, pose, &r, &e);
        /* The chain of boxes follows one branch from the start pose's solution. */
        const bool chained = solved && e.enclosed &&
                             (have_prev ? boxes_meet(&prev, &e) : in_box(&e, q_start) && in_box(&e, q_first));
        piece_timing pt;
        if (proven) {
            pt = piece_bounds(&tm, &e, mv, lim, t0, t1, ud_c, udd_c);
            if (!chained || (!refusing && too_loose(&tm, &pt)))
                proven = false;
        }
        /* Pieces failing a check of the contract (not their timing) at an eighth of the longest
         * proven: the proof is creeping up on a limit.  Every so often a look ahead: a failing
         * segment there makes this a refusal, whose first failure bisection finds. */
        if (!refusing && !(solved && e.proven) && 8u * (s1 - s0) < longest && v->pieces >= scanned + SCAN_EVERY) {
            scanned = v->pieces;
            if (scan_ahead(mv, g, lim, s0, seed, st, v)) {
                refusing = true;
                if (budget > fw_validation_work(v) + REFUSAL_WORK)
                    budget = fw_validation_work(v) + REFUSAL_WORK;
            }
        }
        if (!proven && s1 - s0 > 1) {
            len = (s1 - s0) / 2;
            streak = 0;
            continue;
        }
        if (!proven) {
            /* One segment that cannot be proven as a whole: its end is checked as the
             * per-segment walk checks it (from the centre's slides where there are some), its
             * speeds bounded from the enclosure alone, where there is one. */
            const bool enclosed = solved && e.enclosed;
            if (enclosed)
                copy6(seed, r.q);
            const tse_status why = solved ? e.status : r.status;
            const int why_scissor = solved ? e.scissor : r.scissor;
            fw_move_pose(mv, t1, pose);
            ++v->solves;
            if (tse_ik(g, pose, seed, &r) != TSE_OK) {
                refuse(mv, t1, s1, &r, res);
                return -1;
            }
            if (!enclosed || !chained || !in_box(&e, r.q)) {
                stall_at(st, s1, r.q, why, why_scissor);
                return 1;
            }
            pt = piece_bounds(&tm, &e, mv, lim, t0, t1, ud_c, udd_c);
        } else {
            copy6(seed, r.q);
        }
        account(&tm, &pt);
        keep_box(&prev, &e);
        have_prev = true;
        if (s1 - s0 > longest)
            longest = s1 - s0;
        s0 = s1;
        if (++streak >= GROW_AFTER) {
            streak = 0;
            len = len > n / 2 ? n : 2 * len;
        }
    }
    /* The end pose, as execution's last setpoint: the commanded pose itself. */
    fw_move_pose(mv, mv->prof.T, pose);
    ++v->solves;
    if (tse_ik(g, pose, seed, &r) != TSE_OK) {
        refuse(mv, mv->prof.T, n, &r, res);
        return -1;
    }
    if (!have_prev || !(box_holds(&prev, r.q))) {
        stall_at(st, n, r.q, TSE_SINGULAR, 1);
        return 1;
    }
    copy6(v->q_end, r.q);
    const tse_real span = (tse_real)FW_ACC_STRIDE / lim->segment_hz;
    uint8_t v_slide = 0, a_slide = 0;
    v->v_ratio = TSE_R(0.0);
    v->a_ratio = TSE_R(0.0);
    for (int k = 0; k < 6; ++k) {
        const tse_real first = tse_fabs(q_first[k] - q_from[k]) / t_first / lim->slide_vmax;
        const tse_real vk = first > tm.v[k] ? first : tm.v[k];
        const tse_real ak = tm.a[k] + tse_fabs(q_from[k] - q_start[k]) / (span * span) / lim->slide_amax;
        if (vk > v->v_ratio) {
            v->v_ratio = vk;
            v_slide = (uint8_t)k;
        }
        if (ak > v->a_ratio) {
            v->a_ratio = ak;
            a_slide = (uint8_t)k;
        }
    }
    v->v_slide = v_slide;
    v->a_slide = a_slide;
    v->worst.accel = v->a_ratio > v->v_ratio;
    v->worst.slide = v->worst.accel ? a_slide : v_slide;
    v->worst.ratio = v->worst.accel ? v->a_ratio : v->v_ratio;
    v->per_segment = false;
    return 0;
}

/* A segment between `lo` (which passes, with slides q) and `hi` (which fails with status and
 * scissor) that fails with the one before it passing, found by bisection, as the per-segment walk
 * solves each from the one before: the walk's first failure when the path crosses out of the
 * workspace once between the two. */
static void bisect(const fw_move *mv, const tse_geometry *g, const fw_limits *lim, uint32_t lo, tse_real q[6],
                   uint32_t hi, tse_status status, int scissor, fw_validation *v, fw_plan_result *res)
{
    while (hi - lo > 1u) {
        const uint32_t mid = lo + (hi - lo) / 2u;
        tse_real pose[6];
        tse_ik_result r;
        fw_move_pose(mv, fw_move_segment_time(mv, lim, mid), pose);
        ++v->solves;
        if (tse_ik(g, pose, q, &r) == TSE_OK) {
            lo = mid;
            copy6(q, r.q);
        } else {
            hi = mid;
            status = r.status;
            scissor = r.scissor;
        }
    }
    refuse_at(mv, fw_move_segment_time(mv, lim, hi), hi, status, scissor, res);
}

/* After a stalled proof: a segment known to fail ahead, or one found at doubling distances from the
 * stall (a proof stalls near a limit, so a failure, if any, is likely close), settles it as a
 * refusal at the first failing segment bisection finds (returns -1).  Otherwise 1: the path's
 * sampled segments pass and only the proof could not finish. */
static int settle(const fw_move *mv, const tse_geometry *g, const fw_limits *lim, stall *st, fw_validation *v,
                  fw_plan_result *res)
{
    /* Bisection starts from the later of the stall and the last segment the scan passed. */
    if (st->fail != 0 && st->fail_from < st->at && st->at < st->fail) {
        st->fail_from = st->at;
        copy6(st->fail_q, st->q);
    }
    if (st->fail == 0 && !scan_ahead(mv, g, lim, st->at, st->q, st, v))
        return 1;
    bisect(mv, g, lim, st->fail_from, st->fail_q, st->fail, st->fail_status, st->fail_scissor, v, res);
    return -1;
}

uint32_t fw_validation_work(const fw_validation *v)
{
    return v->solves + (FW_PIECE_WORK - 1u) * v->pieces;
}

int fw_validate(const fw_move *mv, const tse_geometry *g, const fw_limits *lim, const tse_real q_from[6],
                fw_validation *v, fw_plan_result *res)
{
    stall st;
    int rc = prove(mv, g, lim, q_from, v, res, &st);
    if (rc <= 0)
        return rc;
    rc = settle(mv, g, lim, &st, v, res);
    if (rc < 0)
        return rc;
    const uint32_t tried = v->pieces, solves = v->solves;
    if (mv->segments <= FW_VALIDATE_WALK) {
        rc = fw_validate_per_segment(mv, g, lim, q_from, v, res);
        v->pieces = tried;
        v->solves += solves;
        return rc;
    }
    /* Too long to walk within a frame: refused TOO_LONG where the proof stalled, naming the limit it
     * could not prove the path clear of (the path comes closer to it than the proof resolves). */
    const uint32_t at = st.at < mv->segments ? st.at + 1u : mv->segments;
    refuse_at(mv, fw_move_segment_time(mv, lim, at), at, st.why, st.why_scissor, res);
    res->reason = FW_REASON_TOO_LONG;
    if (res->status == TSE_OK)
        res->status = TSE_SINGULAR; /* TSE_OK names a move too long in time */
    v->unproven = true;
    return -1;
}
