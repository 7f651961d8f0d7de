#include "fw/traj.h"

#include "fw/quat.h"
#include "fw/work.h"

static void make_point(fw_traj_point *p, const tse_real pose[6], uint64_t t_us, bool last,
                       const tse_real near_q[4])
{
    for (int k = 0; k < 6; ++k)
        p->pose[k] = pose[k];
    p->v_peak = TSE_R(0.0);
    fw_quat_from_rpy(pose[3], pose[4], pose[5], p->q0);
    /* Keep successive quaternions on one hemisphere so that slerp takes the short way. */
    if (near_q) {
        const tse_real d = p->q0[0] * near_q[0] + p->q0[1] * near_q[1] + p->q0[2] * near_q[2] +
                           p->q0[3] * near_q[3];
        if (d < TSE_R(0.0))
            for (int k = 0; k < 4; ++k)
                p->q0[k] = -p->q0[k];
    }
    p->t_us = t_us;
    p->last = last;
}

void fw_traj_check_start(fw_traj_check *t, const fw_limits *lim, const tse_real pose[6], const tse_real q[6])
{
    t->closed = false;
    make_point(&t->tail, pose, 0u, false, 0);
    /* Speed up to the limit (a stop slows down), acceleration within the path's share of it. */
    fw_slide_check_start(&t->chk, lim->slide_vmax, FW_PATH_MARGIN * lim->slide_amax, lim->segment_hz, q);
    t->next_segment = 1;
}

static void interpolate(const fw_traj_point *a, const fw_traj_point *b, uint64_t tau_us, tse_real pose[6])
{
    if (tau_us >= b->t_us) {
        for (int k = 0; k < 6; ++k)
            pose[k] = b->pose[k];
        return;
    }
    const tse_real u = tau_us <= a->t_us ? TSE_R(0.0)
                                         : (tse_real)(tau_us - a->t_us) / (tse_real)(b->t_us - a->t_us);
    for (int k = 0; k < 3; ++k)
        pose[k] = a->pose[k] + u * (b->pose[k] - a->pose[k]);
    tse_real q[4];
    fw_quat_slerp(a->q0, b->q0, u, q);
    fw_quat_to_rpy(q, &pose[3]);
}

int fw_traj_check_point(const fw_traj_check *t, const tse_geometry *g, const fw_limits *lim, const tse_real pose[6],
                        uint32_t dt_us, bool last, fw_traj_point *p, fw_traj_check *after, fw_plan_result *res)
{
    fw_plan_clear(res);
    if (t->closed) {
        res->reason = FW_REASON_STATE;
        return -1;
    }
    for (int k = 0; k < 6; ++k) {
        if (!isfinite(pose[k])) {
            res->reason = FW_REASON_RANGE;
            return -1;
        }
    }
    const uint64_t period_us = (uint64_t)(TSE_R(1e6) / lim->segment_hz + TSE_R(0.5));
    if (dt_us == 0 || period_us == 0) {
        res->reason = FW_REASON_RANGE;
        return -1;
    }
    make_point(p, pose, t->tail.t_us + dt_us, last, t->tail.q0);

    /* Validate on a copy of the running state: a refused point changes nothing. */
    *after = *t;
    fw_slide_check *chk = &after->chk;
    /* The grid is k segment periods from the start, in whole microseconds like the points. */
    uint32_t k = t->next_segment;
    uint64_t t_prev = (uint64_t)(k - 1u) * period_us;
    for (;; ++k) {
        uint64_t tau = (uint64_t)k * period_us;
        bool at_point = false;
        if (tau >= p->t_us) {
            if (tau > p->t_us && !last)
                break; /* this grid time belongs to the piece after the new point */
            tau = p->t_us; /* the trajectory ends exactly on its last point */
            at_point = true;
        }
        if (fw_work_point()) {
            res->reason = FW_REASON_STATE;
            return -1;
        }
        tse_real sample[6];
        interpolate(&t->tail, p, tau, sample);
        tse_ik_result r;
        if (tse_ik(g, sample, chk->q, &r) != TSE_OK) {
            res->reason = FW_REASON_KINEMATICS;
            res->status = r.status;
            res->scissor = r.scissor;
            res->segment = k;
            res->where = (tse_real)(tau - t->tail.t_us) / (tse_real)dt_us;
            return -1;
        }
        const tse_real dt = (tse_real)(tau - t_prev) * TSE_R(1e-6);
        for (int j = 0; j < 6 && dt > TSE_R(0.0); ++j) {
            const tse_real v = tse_fabs(r.q[j] - chk->q[j]) / dt;
            if (v > p->v_peak)
                p->v_peak = v;
        }
        fw_slide_check_feed(chk, r.q, dt);
        t_prev = tau;
        if (at_point) {
            ++k;
            break;
        }
    }
    if (last)
        fw_slide_check_finish(chk);
    if (!fw_slide_check_ok(chk)) {
        /* Said against slide_amax itself, as for moves. */
        const fw_slide_worst w = fw_slide_check_worst(chk);
        fw_plan_timing(res, w, w.accel ? FW_PATH_MARGIN : TSE_R(1.0), lim);
        return -1;
    }
    after->next_segment = k;
    after->tail = *p;
    after->closed = last;
    return 0;
}

void fw_traj_queue_start(fw_traj_queue *q, const tse_real pose[6])
{
    q->head = 0;
    q->count = 0;
    q->closed = false;
    q->dropped = false;
    make_point(&q->prev, pose, 0u, false, 0);
    q->end_us = 0;
}

int fw_traj_queue_push(fw_traj_queue *q, const fw_traj_point *p, fw_reason *why)
{
    if (q->dropped || q->closed) {
        *why = FW_REASON_STATE;
        return -1;
    }
    if (q->count >= FW_TRAJ_CAPACITY) {
        *why = FW_REASON_QUEUE_FULL;
        return -1;
    }
    q->pts[(q->head + q->count) % FW_TRAJ_CAPACITY] = *p;
    ++q->count;
    q->end_us = p->t_us;
    q->closed = p->last;
    *why = FW_REASON_NONE;
    return 0;
}

bool fw_traj_queue_pose(fw_traj_queue *q, uint64_t tau_us, tse_real pose[6])
{
    /* A point reached becomes the start of the piece after it. */
    while (q->count > 0 && tau_us >= q->pts[q->head].t_us) {
        q->prev = q->pts[q->head];
        q->head = (q->head + 1u) % FW_TRAJ_CAPACITY;
        --q->count;
    }
    if (q->count == 0) {
        for (int k = 0; k < 6; ++k)
            pose[k] = q->prev.pose[k];
        return tau_us <= q->prev.t_us;
    }
    interpolate(&q->prev, &q->pts[q->head], tau_us, pose);
    return true;
}

void fw_traj_queue_drop(fw_traj_queue *q)
{
    q->head = 0;
    q->count = 0;
    q->dropped = true;
}

void fw_traj_start(fw_traj *t, const fw_limits *lim, const tse_real pose[6], const tse_real q[6])
{
    fw_traj_check_start(&t->check, lim, pose, q);
    fw_traj_queue_start(&t->queue, pose);
}

int fw_traj_push(fw_traj *t, const tse_geometry *g, const fw_limits *lim, const tse_real pose[6],
                 uint32_t dt_us, bool last, fw_plan_result *res)
{
    fw_plan_clear(res);
    /* The queue's refusals first: they cost nothing. */
    if (t->queue.dropped) {
        res->reason = FW_REASON_STATE;
        return -1;
    }
    if (t->queue.count >= FW_TRAJ_CAPACITY && !t->check.closed) {
        res->reason = FW_REASON_QUEUE_FULL;
        return -1;
    }
    fw_traj_point p;
    fw_traj_check after;
    if (fw_traj_check_point(&t->check, g, lim, pose, dt_us, last, &p, &after, res) != 0)
        return -1;
    fw_reason why;
    if (fw_traj_queue_push(&t->queue, &p, &why) != 0) {
        res->reason = why;
        return -1;
    }
    t->check = after;
    return 0;
}

bool fw_traj_pose(fw_traj *t, uint64_t tau_us, tse_real pose[6])
{
    return fw_traj_queue_pose(&t->queue, tau_us, pose);
}

void fw_traj_drop(fw_traj *t)
{
    fw_traj_queue_drop(&t->queue);
    t->check.closed = true;
}

uint64_t fw_traj_end_us(const fw_traj *t)
{
    return t->check.tail.t_us;
}
