#include "fw/move.h"

#include "fw/quat.h"
#include "fw/slide_check.h"
#include "fw/validate.h"
#include "fw/work.h"

/* Planning keeps this fraction of every slide limit in hand: the acceleration's for a stop
 * (fw/limits.h), both for the step quantisation. */
#define LIMIT_MARGIN FW_PATH_MARGIN
#define MAX_STRETCH_ROUNDS 6

/* The slerp turns the plate about one world axis at a constant rate: the axis of q1 q0^-1 (q1 on
 * q0's side), times the angle per unit of u. */
static void move_omega(fw_move *mv)
{
    tse_real inv[4], rel[4];
    fw_quat_conj(mv->q0, inv);
    fw_quat_mul(mv->q1, inv, rel);
    const tse_real sgn = rel[0] < TSE_R(0.0) ? TSE_R(-1.0) : TSE_R(1.0);
    const tse_real n = tse_sqrt(rel[1] * rel[1] + rel[2] * rel[2] + rel[3] * rel[3]);
    for (int k = 0; k < 3; ++k)
        mv->omega[k] = n > TSE_R(0.0) ? sgn * rel[k + 1] * mv->angle / n : TSE_R(0.0);
}

/* A limit on the path parameter's speed, acceleration or jerk, and the fw_move_bound it came from. */
typedef struct {
    tse_real v;
    uint8_t by;
} limit_on_u;

static void tighten(limit_on_u *l, tse_real v, uint8_t by)
{
    if (v < l->v) {
        l->v = v;
        l->by = by;
    }
}

/* What set the pace of profile p, planned within V, A and J to last at least min_T: the request
 * when the plan lasts just that (the fastest profile was shorter, and the plan slowed it down to
 * the request; a tie goes to the request); else the speed limit when the profile cruises at it,
 * or, when its ramps meet, whichever of the acceleration and jerk limits gives the longer ramp at
 * its peak speed (fw/profile.h). */
static uint8_t pace_bound(const fw_profile *p, limit_on_u V, limit_on_u A, limit_on_u J, tse_real min_T)
{
    if (p->D == TSE_R(0.0) || (min_T > TSE_R(0.0) && p->T <= min_T * (TSE_R(1.0) + TSE_R(8.0) * TSE_REAL_EPS)))
        return FW_BOUND_ASKED;
    if (p->Tc > TSE_R(0.0))
        return V.by;
    const tse_real by_acc = TSE_R(2.0) * p->V / A.v;
    return by_acc * by_acc >= TSE_R(2.0) * TSE_PI * p->V / J.v ? A.by : J.by;
}

void fw_plan_clear(fw_plan_result *res)
{
    res->reason = FW_REASON_NONE;
    res->status = TSE_OK;
    res->scissor = 0;
    res->segment = 0;
    res->where = TSE_R(0.0);
    res->slide = 0;
    res->accel = false;
    res->limit = FW_LIMIT_SLIDE_VMAX;
    res->ratio = TSE_R(0.0);
}

void fw_plan_timing(fw_plan_result *res, fw_slide_worst w, tse_real scale, const fw_limits *lim)
{
    res->reason = FW_REASON_TIMING;
    res->slide = (uint8_t)(w.slide + 1u);
    res->scissor = w.slide / 2 + 1; /* A_i and B_i are slides 2i - 1 and 2i */
    res->accel = w.accel;
    res->limit = w.accel ? FW_LIMIT_SLIDE_AMAX : lim->vmax_by;
    res->ratio = w.ratio * scale;
}

int fw_move_plan(fw_move *mv, const tse_geometry *g, const fw_limits *lim, const tse_real from[6],
                 const tse_real to[6], fw_move_kind kind, tse_real value, const tse_real q_from[6],
                 fw_plan_result *res)
{
    return fw_move_plan_by(mv, g, lim, from, to, kind, value, q_from, res, fw_validate);
}

int fw_move_plan_by(fw_move *mv, const tse_geometry *g, const fw_limits *lim, const tse_real from[6],
                    const tse_real to[6], fw_move_kind kind, tse_real value, const tse_real q_from[6],
                    fw_plan_result *res, fw_validator validate)
{
    fw_plan_clear(res);
    for (int k = 0; k < 6; ++k) {
        if (!isfinite(from[k]) || !isfinite(to[k]) || !isfinite(q_from[k])) {
            res->reason = FW_REASON_RANGE;
            return -1;
        }
        mv->from[k] = from[k];
        mv->to[k] = to[k];
        mv->q_from[k] = q_from[k];
    }
    if (!(value > TSE_R(0.0)) || !isfinite(value)) {
        res->reason = FW_REASON_RANGE;
        return -1;
    }
    tse_real len2 = TSE_R(0.0);
    for (int k = 0; k < 3; ++k) {
        mv->dp[k] = to[k] - from[k];
        len2 += mv->dp[k] * mv->dp[k];
    }
    mv->length = tse_sqrt(len2);
    fw_quat_from_rpy(from[3], from[4], from[5], mv->q0);
    fw_quat_from_rpy(to[3], to[4], to[5], mv->q1);
    mv->angle = fw_quat_angle(mv->q0, mv->q1);
    move_omega(mv);
    mv->stretch = TSE_R(1.0);

    /* Limits on u: whichever of translation and rotation binds, and which limit that is.  The
     * angular jerk limit keeps the plate's ramp-time character: dwmax * jmax / amax. */
    const tse_real huge = (tse_real)INFINITY;
    limit_on_u V = {huge, 0}, A = {huge, 0}, J = {huge, 0};
    if (mv->length > TSE_R(0.0)) {
        tighten(&V, lim->plate_vmax / mv->length, FW_BOUND_PLATE_VMAX);
        tighten(&A, lim->plate_amax / mv->length, FW_BOUND_PLATE_AMAX);
        tighten(&J, lim->plate_jmax / mv->length, FW_BOUND_PLATE_JMAX);
        if (kind == FW_MOVE_SPEED)
            tighten(&V, value / mv->length, FW_BOUND_ASKED);
    }
    if (mv->angle > TSE_R(0.0)) {
        tighten(&V, lim->plate_wmax / mv->angle, FW_BOUND_PLATE_WMAX);
        tighten(&A, lim->plate_dwmax / mv->angle, FW_BOUND_PLATE_DWMAX);
        tighten(&J, lim->plate_dwmax * lim->plate_jmax / lim->plate_amax / mv->angle, FW_BOUND_PLATE_JMAX_ANGULAR);
    }
    const tse_real min_T = kind == FW_MOVE_DURATION ? value : TSE_R(0.0);
    const tse_real D = (mv->length > TSE_R(0.0) || mv->angle > TSE_R(0.0)) ? TSE_R(1.0) : TSE_R(0.0);
    if (D == TSE_R(0.0))
        V.v = A.v = J.v = TSE_R(1.0); /* a null move: only its duration matters */
    if (fw_profile_plan(&mv->prof, D, V.v, A.v, J.v, min_T) != 0) {
        res->reason = FW_REASON_RANGE;
        return -1;
    }
    mv->bound = pace_bound(&mv->prof, V, A, J, min_T);
    mv->bound_slide = 0;
    mv->bound_ratio = TSE_R(0.0);

    fw_limits margin = *lim;
    margin.slide_vmax *= LIMIT_MARGIN;
    margin.slide_amax *= LIMIT_MARGIN;
    fw_slide_worst worst = {0, false, TSE_R(0.0)};
    uint32_t work = 0;
    for (int round = 0; round < MAX_STRETCH_ROUNDS && work < 2u * FW_VALIDATE_WORK; ++round) {
        /* Counted before it is converted: a move of metres at micrometres a second has billions of
         * segments, beyond a uint32_t and beyond any use. */
        const tse_real segs = tse_ceil(mv->prof.T * lim->segment_hz);
        if (!(segs <= (tse_real)FW_MOVE_MAX_S * lim->segment_hz)) {
            res->reason = FW_REASON_TOO_LONG;
            res->status = TSE_OK; /* too long in time, not near a limit */
            res->where = (tse_real)FW_MOVE_MAX_S;
            return -1;
        }
        mv->segments = segs < TSE_R(1.0) ? 1u : (uint32_t)segs;
        fw_validation val;
        if (validate(mv, g, &margin, q_from, &val, res) != 0)
            return -1;
        work += fw_validation_work(&val);
        for (int k = 0; k < 6; ++k)
            mv->q_end[k] = val.q_end[k];
        const tse_real vr = val.v_ratio, ar = val.a_ratio;
        worst = val.worst;
        /* Speeds scale with 1/k and accelerations with 1/k^2 under a time stretch by k. */
        tse_real k = vr;
        const tse_real ka = tse_sqrt(ar);
        if (ka > k)
            k = ka;
        if (k <= TSE_R(1.0)) {
            mv->v_peak = vr * margin.slide_vmax;
            return 0;
        }
        if (round == 0) {
            /* The slides set the pace: the demand that asked for the longer stretch (k above), at
             * the pace before it, against its limit in effect. */
            const bool accel = ka > vr;
            mv->bound = accel                                      ? FW_BOUND_SLIDE_AMAX
                        : lim->vmax_by == FW_LIMIT_STEP_GENERATOR ? FW_BOUND_STEP_GENERATOR
                                                                   : FW_BOUND_SLIDE_VMAX;
            mv->bound_slide = (uint8_t)((accel ? val.a_slide : val.v_slide) + 1u);
            mv->bound_ratio = (accel ? ar : vr) * LIMIT_MARGIN;
        }
        /* Sampling moves with the stretch, so aim a little beyond the measured need. */
        k *= TSE_R(1.02);
        fw_profile_stretch(&mv->prof, k);
        mv->stretch *= k;
    }
    /* Still too fast after every round (or after as much validation as three rounds may do, which
     * bounds a commit's time): refuse rather than exceed a limit, naming the last walk's worst
     * slide. */
    fw_plan_timing(res, worst, LIMIT_MARGIN, lim);
    return -1;
}

void fw_move_blend_pose(const fw_move *a, const fw_move *b, uint32_t k0, const fw_limits *lim, tse_real t,
                        tse_real pose[6])
{
    const tse_real t0 = (tse_real)k0 / lim->segment_hz;
    if (t < t0) {
        fw_move_pose(a, t, pose);
        return;
    }
    if (t >= a->prof.T) {
        fw_move_pose(b, t - t0, pose);
        return;
    }
    /* a's pose, plus b's progress since its start: b's displacement added, b's rotation
     * increment (b->q1 b->q0^-1)^u composed onto a's orientation. */
    tse_real u_a, u_b, du, ddu;
    fw_profile_eval(&a->prof, t, &u_a, &du, &ddu);
    fw_profile_eval(&b->prof, t - t0, &u_b, &du, &ddu);
    for (int k = 0; k < 3; ++k)
        pose[k] = a->from[k] + u_a * a->dp[k] + u_b * b->dp[k];
    tse_real qa[4], inv[4], rel[4], step[4], q[4];
    static const tse_real identity[4] = {TSE_R(1.0), TSE_R(0.0), TSE_R(0.0), TSE_R(0.0)};
    fw_quat_slerp(a->q0, a->q1, u_a, qa);
    fw_quat_conj(b->q0, inv);
    fw_quat_mul(b->q1, inv, rel);
    fw_quat_slerp(identity, rel, u_b, step);
    fw_quat_mul(step, qa, q);
    fw_quat_to_rpy(q, &pose[3]);
}

int fw_move_blend(const fw_move *a, const fw_move *b, const tse_geometry *g, const fw_limits *lim,
                  uint32_t earliest, uint32_t *k0)
{
    *k0 = a->segments;
    const tse_real overlap = a->prof.Ta < b->prof.Ta ? a->prof.Ta : b->prof.Ta;
    const tse_real start = (a->prof.T - overlap) * lim->segment_hz;
    if (!(start > TSE_R(0.0)) || b->segments == 0)
        return 1;
    const uint32_t k = (uint32_t)tse_ceil(start);
    if (k < earliest || k >= a->segments)
        return 1;
    /* Walk a then b with the blend, as execution will, from a's start. */
    const tse_real t0 = (tse_real)k / lim->segment_hz;
    const uint32_t total = k + b->segments;
    fw_slide_check chk;
    fw_slide_check_start(&chk, lim->slide_vmax * LIMIT_MARGIN, lim->slide_amax * LIMIT_MARGIN,
                         lim->segment_hz, a->q_from);
    tse_real t_prev = TSE_R(0.0);
    for (uint32_t s = 1; s <= total; ++s) {
        if (fw_work_point())
            return 1; /* stopped from outside (fw/work.h): no blend */
        tse_real t = (tse_real)s / lim->segment_hz;
        if (s == total)
            t = t0 + b->prof.T;
        tse_real pose[6];
        fw_move_blend_pose(a, b, k, lim, t, pose);
        tse_ik_result r;
        if (tse_ik(g, pose, chk.q, &r) != TSE_OK)
            return 1;
        fw_slide_check_feed(&chk, r.q, t - t_prev);
        t_prev = t;
    }
    fw_slide_check_finish(&chk);
    if (!fw_slide_check_ok(&chk))
        return 1;
    *k0 = k;
    return 0;
}
