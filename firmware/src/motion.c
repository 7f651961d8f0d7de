#include "motion.h"

#include "homing.h"
#include "steps.h"
#include "traj_life.h"

/* Setpoints the control tick keeps queued ahead of the step interrupt. */
#define QUEUE_AHEAD 2u
/* Shortest controlled stop [s]. */
#define MIN_STOP_TIME TSE_R(0.02)

/* The fastest slide's speed over the last control period. */
static tse_real present_speed(const fw_controller *c)
{
    const fw_tick *t = &c->tick;
    tse_real v = TSE_R(0.0);
    for (int k = 0; k < 6; ++k) {
        const tse_real vk = tse_fabs(t->q[k] - t->q_prev[k]) * (tse_real)c->cfg.segment_hz;
        if (vk > v)
            v = vk;
    }
    return v;
}

/* The stop ramp of a move or of homing's joint move (cycloidal: a slide moving at v brakes at most
 * 2 v / T), one that holds for the whole path, whatever its own acceleration: the ramp scales the
 * path's time rate r from 1 to 0 (advance), so a slide's acceleration is r^2 times the path's
 * own (at most `along` of the limit) plus r' times the path's slide speed.  That speed goes on
 * growing while the ramp stretches time along an accelerating path, so a ramp sized from the
 * present speed can brake beyond the limit; sized from the fastest the path's slides
 * go (v_peak), with `share` of the limit for braking, the sum is at most the peak over the ramp's
 * x in [0, 1] of along r(x)^2 + share (1 - cos 2 pi x) / 2: for along 0.95 and share 0.4 (a
 * move, planned within 95 % of the limits), 0.998 of the limit; for 0.9 and 0.45 (homing's
 * joint move), 0.972. */
static tse_real path_stop_time(const fw_controller *c, tse_real v_peak, tse_real share)
{
    const tse_real T = TSE_R(2.0) * v_peak / (share * c->tick.lim.slide_amax);
    return T < MIN_STOP_TIME ? MIN_STOP_TIME : T;
}

/* The fastest a slide goes along the queued trajectory from the present over the next `span`
 * seconds of path time: what each queued piece's validation measured (fw_traj_point.v_peak). */
static tse_real traj_v_peak(const fw_controller *c, tse_real span)
{
    const fw_traj_queue *q = &c->tick.traj;
    const uint64_t until = (uint64_t)((c->tick.tau + span) * TSE_R(1e6));
    tse_real v = TSE_R(0.0);
    for (unsigned i = 0; i < q->count; ++i) {
        const fw_traj_point *p = &q->pts[(q->head + i) % FW_TRAJ_CAPACITY];
        if (p->v_peak > v)
            v = p->v_peak;
        if (p->t_us >= until)
            break;
    }
    return v;
}

/* A trajectory's stop ramp (fw/traj_stop.h), sized from the fastest its slides go over the path
 * time the ramp covers (and a stride more), not from the present speed: a path still accelerating
 * goes on speeding up along the ramp (issue 24: braking at 1.3 times slide_amax).  The ramp's
 * length and the span it covers grow together; a few rounds settle them. */
static tse_real traj_stop_time(const fw_controller *c)
{
    const fw_tick *t = &c->tick;
    const tse_real stride = (tse_real)FW_ACC_STRIDE / (tse_real)c->cfg.segment_hz;
    const tse_real v = present_speed(c);
    tse_real T = fw_traj_stop_time(v, t->lim.slide_amax, MIN_STOP_TIME);
    for (int round = 0; round < 8; ++round) {
        const tse_real v_peak = traj_v_peak(c, fw_traj_stop_reach(T) + stride);
        const tse_real longer = fw_traj_stop_time(v_peak > v ? v_peak : v, t->lim.slide_amax, MIN_STOP_TIME);
        if (!(longer > T))
            break;
        T = longer;
    }
    return T;
}

/* The fastest a slide goes along homing's joint move: its cruise speed on the longest slide. */
static tse_real joint_v_peak(const fw_controller *c)
{
    const fw_joint_move *j = &c->tick.joint;
    tse_real longest = TSE_R(0.0);
    for (int k = 0; k < 6; ++k) {
        const tse_real d = tse_fabs(j->to[k] - j->from[k]);
        if (d > longest)
            longest = d;
    }
    return j->prof.V * longest;
}

void fw_motion_start(fw_controller *c, fw_source src)
{
    fw_tick *t = &c->tick;
    t->src = src;
    t->has_next = false;
    t->tau = TSE_R(0.0);
    t->segments_run = 0;
    t->stopping = false;
    fw_set_state(c, FW_STATE_MOVING);
}

fw_move_start fw_motion_join(fw_controller *c, const fw_move *next, bool blend, uint32_t k0)
{
    fw_tick *t = &c->tick;
    if (t->src != FW_SRC_MOVE || t->stopping || t->has_next || t->state != FW_STATE_MOVING)
        return FW_START_COUNT;
    t->next = *next;
    t->has_next = true;
    /* The blend was walked from the running move's start, as execution runs it: it holds while
     * no setpoint past its first segment has been computed. */
    if (blend && k0 < t->move.segments && t->segments_run <= k0) {
        t->blend_k0 = k0;
        return FW_START_BLENDED;
    }
    t->blend_k0 = t->move.segments;
    return FW_START_AFTER;
}

void fw_motion_stop(fw_controller *c)
{
    fw_tick *t = &c->tick;
    if (t->home.active) {
        /* Seeking and releasing have no path to slow down along: homing ramps its joint speeds
         * down itself.  Its final joint move stops like any source, below. */
        t->home.abort = true;
        fw_set_state(c, FW_STATE_STOPPING);
        if (t->src == FW_SRC_NONE)
            return;
    }
    if (t->src == FW_SRC_NONE) {
        /* Nothing runs along the queue any more (at rest, or the last setpoints stepping out: a
         * trajectory that got there ran to its last row, or held its newest row and faulted). */
        fw_traj_life_end_pending(c, FW_TRAJ_END_DONE);
        fw_traj_queue_drop(&t->traj);
        return;
    }
    if (t->stopping)
        return;
    if (t->src == FW_SRC_TRAJ) {
        const bool clocked = t->traj_clock;
        /* From here on the trajectory takes no row: it ended now, by this stop or a fault. */
        fw_traj_life_end_pending(c, FW_TRAJ_END_STOP);
        if (!clocked) {
            /* Its clock never started: the plate is at rest where it was. */
            t->src = FW_SRC_NONE;
            fw_traj_queue_drop(&t->traj);
            fw_set_state(c, FW_STATE_STOPPING);
            return;
        }
    }
    fw_set_state(c, FW_STATE_STOPPING);
    /* Once a queued move has begun to blend in, the slides are on the sum of the two paths: the
     * stop must follow that path, for dropping the second move would send them back to the
     * first's at once.  Before, the path is the running move's alone. */
    const bool blending = t->src == FW_SRC_MOVE && t->has_next &&
                          t->tau >= (tse_real)t->blend_k0 / (tse_real)c->cfg.segment_hz;
    if (!blending)
        t->has_next = false;
    if (t->src == FW_SRC_MOVE && !blending && t->tau >= t->move.prof.T - t->move.prof.Ta) {
        /* Already on its final ramp, which stops within the limits: a second braking on top of
         * it would not. */
        return;
    }
    /* Moves and homing's joint move brake within the limit over their whole path (path_stop_time;
     * the slide speeds of a blend's two moves at most add); a trajectory's path is the host's,
     * still arriving, so its braking takes half the limit from the present speed. */
    t->stopping = true;
    t->stop_t = TSE_R(0.0);
    if (t->src == FW_SRC_JOINT)
        t->stop_T = path_stop_time(c, joint_v_peak(c), TSE_R(0.45));
    else if (t->src == FW_SRC_MOVE)
        t->stop_T = path_stop_time(c, t->move.v_peak + (blending ? t->next.v_peak : TSE_R(0.0)), TSE_R(0.4));
    else {
        t->stop_T = traj_stop_time(c);
        fw_traj_stop_begin(&t->traj_stop, t->stop_T, TSE_R(1.0) / (tse_real)c->cfg.segment_hz);
    }
}

/* Path time of the next segment: on the planner's grid exactly while running, so execution
 * solves the very poses validation solved; along the stop ramp when stopping.  *last is set on
 * the segment that ends the ramp or the source. */
static tse_real advance(fw_controller *c, tse_real end, bool *last)
{
    fw_tick *t = &c->tick;
    const tse_real dt = TSE_R(1.0) / (tse_real)c->cfg.segment_hz;
    *last = false;
    if (t->stopping) {
        t->stop_t += dt;
        tse_real rate = TSE_R(0.0);
        if (t->stop_t >= t->stop_T) {
            *last = true;
        } else if (t->src == FW_SRC_TRAJ) {
            rate = fw_traj_stop_next(&t->traj_stop);
        } else {
            const tse_real x = t->stop_t / t->stop_T;
            rate = TSE_R(1.0) - (x - tse_sin(TSE_R(2.0) * TSE_PI * x) / (TSE_R(2.0) * TSE_PI));
        }
        tse_real tau = t->tau + rate * dt;
        if (tau >= end) {
            tau = end;
            *last = true;
        }
        return tau;
    }
    tse_real tau = (tse_real)(t->segments_run + 1u) / (tse_real)c->cfg.segment_hz;
    if (tau >= end) {
        tau = end;
        *last = true;
    }
    return tau;
}

static void push_slides(fw_controller *c, const tse_real q[6])
{
    fw_tick *t = &c->tick;
    int32_t target[STEPGEN_AXES];
    for (int k = 0; k < 6; ++k) {
        target[k] = fw_steps_of(&t->params, q[k]);
        t->q_prev[k] = t->q[k];
        t->q[k] = q[k];
    }
    stepgen_push(&c->sg, target);
    ++t->segments_run;
}

/* One control segment of a pose source: advance path time, solve, queue the setpoint. */
static void run_source(fw_controller *c)
{
    fw_tick *t = &c->tick;
    bool last;
    tse_real end;
    const tse_real t0 = (tse_real)t->blend_k0 / (tse_real)c->cfg.segment_hz;
    if (t->src == FW_SRC_MOVE)
        end = t->has_next ? t0 + t->next.prof.T : t->move.prof.T;
    else
        end = t->traj.closed ? (tse_real)t->traj.end_us * TSE_R(1e-6) : (tse_real)INFINITY;
    const uint32_t grid = t->segments_run + 1u;
    const tse_real tau = advance(c, end, &last);
    tse_real pose[6];
    bool inside = true;
    if (t->src == FW_SRC_TRAJ && !t->traj.closed && !t->stopping) {
        /* The host is falling behind: once less trajectory is queued than a stop needs, stop
         * along it while there is room, and latch the underrun. */
        const tse_real left = (tse_real)t->traj.end_us * TSE_R(1e-6) - t->tau;
        if (left <= fw_traj_stop_reach(traj_stop_time(c)) + TSE_R(2.0) / (tse_real)c->cfg.segment_hz) {
            t->pending_fault = FW_FAULT_UNDERRUN;
            fw_motion_stop(c);
        }
    }
    if (t->src == FW_SRC_MOVE) {
        if (t->has_next)
            fw_move_blend_pose(&t->move, &t->next, t->blend_k0, &t->lim, tau, pose);
        else
            fw_move_pose(&t->move, tau, pose);
    } else {
        /* On the grid the time is exact in microseconds, as validation sampled it. */
        uint64_t tau_us = t->stopping ? (uint64_t)(tau * TSE_R(1e6) + TSE_R(0.5))
                                      : (uint64_t)grid * (1000000u / c->cfg.segment_hz);
        /* The last point exactly, when the path has reached it; a stop ramp that ends before it
         * ends where the ramp brought the slides. */
        if (last && t->traj.closed && tau >= end)
            tau_us = t->traj.end_us;
        inside = fw_traj_queue_pose(&t->traj, tau_us, pose);
    }
    if (!inside) {
        /* The stream ran dry before its last point: hold its newest point, and fault. */
        last = true;
        t->pending_fault = FW_FAULT_UNDERRUN;
        fw_traj_life_end(c, FW_TRAJ_END_FAULT, FW_FAULT_UNDERRUN);
    }
    tse_ik_result r;
    if (tse_ik(&t->geom, pose, t->q, &r) != TSE_OK) {
        /* Validation solved this path, so this is a defect: there is no pose to go on to. */
        t->src = FW_SRC_NONE;
        t->pending_fault = FW_FAULT_PLANNER;
        fw_traj_life_end(c, FW_TRAJ_END_FAULT, FW_FAULT_PLANNER);
        return;
    }
    for (int k = 0; k < 6; ++k)
        t->pose[k] = pose[k];
    push_slides(c, r.q);
    t->tau = tau;
    if (t->src == FW_SRC_MOVE && t->has_next && tau >= t->move.prof.T && !last) {
        /* The first move is over: the second goes on alone, on the same grid. */
        t->move = t->next;
        t->has_next = false;
        t->segments_run -= t->blend_k0;
        t->tau -= t0;
    }
    if (last) {
        t->src = FW_SRC_NONE;
        t->has_next = false;
    }
}

/* The joint-space move that ends homing: straight in slide space. */
static void run_joint(fw_controller *c)
{
    fw_tick *t = &c->tick;
    bool last;
    const tse_real tau = advance(c, t->joint.prof.T, &last);
    tse_real u, du, ddu;
    fw_profile_eval(&t->joint.prof, tau, &u, &du, &ddu);
    tse_real q[6];
    for (int k = 0; k < 6; ++k)
        q[k] = tau >= t->joint.prof.T ? t->joint.to[k] : t->joint.from[k] + u * (t->joint.to[k] - t->joint.from[k]);
    push_slides(c, q);
    t->tau = tau;
    if (last)
        t->src = FW_SRC_NONE;
}

fw_motion_outcome fw_motion_tick(fw_controller *c)
{
    fw_tick *t = &c->tick;
    if (t->home.active && t->src == FW_SRC_NONE)
        return fw_homing_tick(c) == FW_HOMING_ENDED ? FW_MOTION_HOMING_ENDED : FW_MOTION_RUNS;
    /* A trajectory whose queue is still filling holds the plate at rest. */
    const bool priming = t->src == FW_SRC_TRAJ && fw_traj_life_priming(c);
    while (!priming && t->src != FW_SRC_NONE && stepgen_queued(&c->sg) < QUEUE_AHEAD) {
        if (t->src == FW_SRC_JOINT)
            run_joint(c);
        else
            run_source(c);
    }
    if (t->src != FW_SRC_NONE || !stepgen_idle(&c->sg))
        return FW_MOTION_RUNS;
    /* The source is exhausted and the slides are at their last setpoint. */
    if (t->home.active) /* the joint move to the home pose ended */
        return fw_homing_tick(c) == FW_HOMING_ENDED ? FW_MOTION_HOMING_ENDED : FW_MOTION_RUNS;
    if (t->state != FW_STATE_MOVING && t->state != FW_STATE_STOPPING)
        return FW_MOTION_RUNS;
    /* At rest: what a stop ramp left of the trajectory is not for running any more. */
    t->stopping = false;
    fw_traj_life_end_pending(c, FW_TRAJ_END_DONE);
    fw_traj_queue_drop(&t->traj);
    return FW_MOTION_AT_REST;
}
