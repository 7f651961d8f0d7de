/* State, safety supervision and the execution of motion at the control segment rate. */
#include "fw/controller_internal.h"

#include <string.h>

#include "fw/limits.h"
#include "tse/fk.h"

/* Setpoints the control loop keeps queued ahead of the step interrupt. */
#define QUEUE_AHEAD 2u
/* Shortest controlled stop [s]. */
#define MIN_STOP_TIME TSE_R(0.02)

static uint64_t now_us(fw_controller *c)
{
    return c->hal.clock.now_us(c->hal.clock.ctx);
}

int32_t fw_to_steps(const fw_controller *c, tse_real s)
{
    const tse_real x = s * (tse_real)c->params.v[FP_STEPS_PER_M];
    return (int32_t)(x >= TSE_R(0.0) ? x + TSE_R(0.5) : x - TSE_R(0.5));
}

void fw_set_state(fw_controller *c, fw_state s)
{
    c->state = s;
}

void fw_drives(fw_controller *c, bool on)
{
    c->drives_on = on;
    c->hal.stepper.enable(c->hal.stepper.ctx, on);
    /* An e-stop interrupt just before the enable would be undone by it: look after it.  Either
     * the request shows here, or the interrupt's own switch-off comes after ours. */
    if (on && atomic_load(&c->estop_request)) {
        c->drives_on = false;
        c->hal.stepper.enable(c->hal.stepper.ctx, false);
    }
}

/* Whole steps of a length in micrometres (integer: the same on the float board build). */
static int32_t um_to_steps(const fw_param_set *s, int32_t um)
{
    const int64_t x = (int64_t)um * s->v[FP_STEPS_PER_M];
    return (int32_t)((x >= 0 ? x + 500000 : x - 500000) / 1000000);
}

int32_t fw_home_switch_steps(const fw_controller *c, int k)
{
    /* The last whole step at or below the switch (home_sw_k >= s_min >= 0): pressed there. */
    return (int32_t)((int64_t)c->params.v[FP_HOME_SW_1 + k] * c->params.v[FP_STEPS_PER_M] / 1000000);
}

fw_param_rule fw_apply_params(fw_controller *c, const fw_param_set *s)
{
    tse_geometry g;
    fw_limits lim;
    stepgen_config sc;
    const fw_param_rule rule = fw_params_judge_config(s, c->cfg.step_hz, c->cfg.segment_hz).rule;
    if (rule != FW_RULE_NONE)
        return rule;
    if (fw_limits_from_params(s, c->cfg.step_hz, c->cfg.segment_hz, &g, &lim) != 0 ||
        fw_stepgen_config_from_params(s, c->cfg.step_hz, c->cfg.segment_hz, &sc) != FW_RULE_NONE)
        return FW_RULE_GEOMETRY; /* what the judge passed, these take: not reached */
    int32_t pos[STEPGEN_AXES];
    stepgen_positions(&c->sg, pos);
    if (!stepgen_idle(&c->sg) || stepgen_init(&c->sg, &sc, pos) != 0)
        return FW_RULE_NOT_AT_REST; /* parameters change only at rest */
    c->overruns_seen = 0; /* the fresh generator counts from zero */
    /* A fresh generator is not halted: an e-stop interrupt before it asked for a halt that must
     * last until the request is completed (the generator is idle, so no step came in between). */
    if (atomic_load(&c->estop_request))
        stepgen_halt(&c->sg);
    /* A fresh generator assumes its direction mask: make the pins agree with it. */
    c->hal.stepper.set_dir(c->hal.stepper.ctx, c->sg.forward_mask);
    if (c->hal.stepper.timing)
        c->hal.stepper.timing(c->hal.stepper.ctx, (uint32_t)s->v[FP_STEP_PULSE_NS],
                              (uint32_t)s->v[FP_DIR_SETUP_NS]);
    /* The zero was set against the old switch positions and step size. */
    bool rezero = s->v[FP_STEPS_PER_M] != c->params.v[FP_STEPS_PER_M];
    for (int k = 0; k < 6; ++k)
        rezero = rezero || s->v[FP_HOME_SW_1 + k] != c->params.v[FP_HOME_SW_1 + k];
    /* A new geometry or stroke: the pose the slides hold, and whether they are inside the stroke,
     * are other than what was known; homing again establishes both (the margins only judge
     * future paths, so they keep it). */
    for (int id = FP_L; id <= FP_S_MAX; ++id)
        rezero = rezero || s->v[id] != c->params.v[id];
    if (rezero) {
        c->homed = false;
        c->pose_known = false;
    }
    c->params = *s;
    c->geom = g;
    c->lim = lim;
    return FW_RULE_NONE;
}

int fw_init(fw_controller *c, const fw_hal *hal, const fw_config *cfg)
{
    memset(c, 0, sizeof *c);
    /* Trajectory time is kept in whole microseconds: the segment period must be one. */
    if (cfg->node == 0 || cfg->node > PROTO_NODE_MASK || cfg->segment_hz == 0 ||
        1000000u % cfg->segment_hz != 0 || cfg->step_hz % cfg->segment_hz != 0)
        return -1;
    c->hal = *hal;
    c->cfg = *cfg;
    c->state = FW_STATE_BOOT;
    atomic_init(&c->estop_request, false);

    fw_param_set s;
    fw_params_default(&s);
    uint8_t buf[256];
    const int n = hal->storage.load(hal->storage.ctx, buf, sizeof buf);
    if (n > 0)
        fw_params_deserialize(&s, buf, (size_t)n); /* a bad record leaves the defaults */
    if (fw_apply_params(c, &s) != 0) {
        fw_params_default(&s);
        if (fw_apply_params(c, &s) != 0)
            return -1;
    }
    fw_traj_start(&c->traj, &c->lim, c->geom.home_pose, c->q);
    fw_drives(c, false);
    const uint64_t t = now_us(c);
    c->next_status_us = t;
    c->next_telemetry_us = t;
    fw_set_state(c, FW_STATE_DISABLED);
    return 0;
}

void fw_estop(fw_controller *c)
{
    /* Stepping ends now, not after a ramp: the queued segments go too. */
    stepgen_abort(&c->sg);
    fw_drives(c, false);
    c->src = FW_SRC_NONE;
    c->has_next = false;
    c->stopping = false;
    c->home.active = false;
    c->homed = false; /* steps may have been lost under the abrupt stop: home again */
    c->pose_known = false;
    fw_traj_drop(&c->traj);
    fw_traj_run_end(c, FW_TRAJ_END_FAULT, FW_FAULT_ESTOP);
    c->fault = FW_FAULT_ESTOP;
    c->pending_fault = FW_FAULT_NONE;
    fw_set_state(c, FW_STATE_ESTOP);
}

void fw_estop_isr(fw_controller *c)
{
    /* Stepping first: it is what must stop at once.  The request last, so that whoever completes
     * it finds the halt already in place. */
    stepgen_halt(&c->sg);
    c->hal.stepper.enable(c->hal.stepper.ctx, false);
    atomic_store(&c->estop_request, true);
}

void fw_estop_complete(fw_controller *c)
{
    if (atomic_exchange(&c->estop_request, false))
        fw_estop(c);
}

static void latch_fault(fw_controller *c, fw_fault f)
{
    fw_traj_run_end(c, FW_TRAJ_END_FAULT, f);
    c->fault = f;
    c->pending_fault = FW_FAULT_NONE;
    c->src = FW_SRC_NONE;
    c->has_next = false;
    c->stopping = false;
    c->home.active = false;
    fw_traj_drop(&c->traj);
    fw_drives(c, false);
    fw_set_state(c, FW_STATE_FAULT);
}

/* Length of a stop ramp of the path's time rate from 1 to 0 (cycloidal): a slide moving at v
 * brakes at most 2 v / T.  `share` is the part of the acceleration limit the braking may take;
 * the path's own acceleration has the rest. */
static tse_real stop_time(const fw_controller *c, tse_real share)
{
    tse_real v = TSE_R(0.0);
    for (int k = 0; k < 6; ++k) {
        const tse_real vk = tse_fabs(c->q[k] - c->q_prev[k]) * (tse_real)c->cfg.segment_hz;
        if (vk > v)
            v = vk;
    }
    tse_real T = TSE_R(2.0) * v / (share * c->lim.slide_amax);
    return T < MIN_STOP_TIME ? MIN_STOP_TIME : T;
}

/* A stop ramp that holds for the whole path, whatever its own acceleration: the ramp scales the
 * path's time rate r from 1 to 0 (advance), so a slide's acceleration is r^2 times the path's
 * own (at most `along` of the limit) plus r' times the path's slide speed.  That speed goes on
 * growing while the ramp stretches time along an accelerating path, so a ramp sized from the
 * present speed (stop_time) can brake beyond the limit; sized from the fastest the path's slides
 * go (v_peak), with `share` of the limit for braking, the sum is at most the peak over the ramp's
 * x in [0, 1] of along r(x)^2 + share (1 - cos 2 pi x) / 2: for along 0.95 and share 0.4 (a
 * move, planned within 95 % of the limits), 0.998 of the limit; for 0.9 and 0.45 (homing's
 * joint move), 0.972. */
/* The share of slide_amax a trajectory's stop brakes with (its path is validated up to the limit
 * itself: along 1, below). */
#define TRAJ_STOP_SHARE TSE_R(0.45)

static tse_real path_stop_time(const fw_controller *c, tse_real v_peak, tse_real share)
{
    const tse_real T = TSE_R(2.0) * v_peak / (share * c->lim.slide_amax);
    return T < MIN_STOP_TIME ? MIN_STOP_TIME : T;
}

/* The fastest a slide goes along the queued trajectory from the present over the next `span`
 * seconds of path time: what each queued piece's validation measured (fw_traj_point.v_peak). */
static tse_real traj_v_peak(const fw_controller *c, tse_real span)
{
    const uint64_t until = (uint64_t)((c->tau + span) * TSE_R(1e6));
    tse_real v = TSE_R(0.0);
    for (unsigned i = 0; i < c->traj.count; ++i) {
        const fw_traj_point *p = &c->traj.pts[(c->traj.head + i) % FW_TRAJ_CAPACITY];
        if (p->v_peak > v)
            v = p->v_peak;
        if (p->t_us >= until)
            break;
    }
    return v;
}

/* A trajectory's stop ramp, sized as a move's (path_stop_time) from the fastest its slides go over
 * the path time the ramp covers (half its length, and a stride more), not from the present speed:
 * a path still accelerating goes on speeding up along the ramp (issue 24: braking at 1.3 times
 * slide_amax).  The ramp's length and the span it covers grow together; a few rounds settle them. */
static tse_real traj_stop_time(const fw_controller *c, tse_real share)
{
    const tse_real stride = (tse_real)FW_ACC_STRIDE / (tse_real)c->cfg.segment_hz;
    tse_real T = stop_time(c, share);
    for (int round = 0; round < 8; ++round) {
        const tse_real longer = path_stop_time(c, traj_v_peak(c, TSE_R(0.5) * T + stride), share);
        if (!(longer > T))
            break;
        T = longer;
    }
    return T;
}

/* The fastest a slide goes along homing's joint move: its cruise speed on the longest slide. */
static tse_real joint_v_peak(const fw_controller *c)
{
    tse_real longest = TSE_R(0.0);
    for (int k = 0; k < 6; ++k) {
        const tse_real d = tse_fabs(c->joint.to[k] - c->joint.from[k]);
        if (d > longest)
            longest = d;
    }
    return c->joint.prof.V * longest;
}

void fw_stop_motion(fw_controller *c)
{
    if (c->home.active) {
        /* Seeking and releasing have no path to slow down along: homing ramps its joint speeds
         * down itself.  Its final joint move stops like any source, below. */
        c->home.abort = true;
        fw_set_state(c, FW_STATE_STOPPING);
        if (c->src == FW_SRC_NONE)
            return;
    }
    if (c->src == FW_SRC_NONE) {
        /* Nothing runs along the queue any more (at rest, or the last setpoints stepping out: a
         * trajectory that got there ran to its last row, or held its newest row and faulted). */
        fw_traj_run_end_pending(c, FW_TRAJ_END_DONE);
        fw_traj_drop(&c->traj);
        return;
    }
    if (c->stopping)
        return;
    if (c->src == FW_SRC_TRAJ) {
        const bool clocked = c->run.clock;
        /* From here on the trajectory takes no row: it ended now, by this stop or a fault. */
        fw_traj_run_end_pending(c, FW_TRAJ_END_STOP);
        if (!clocked) {
            /* Its clock never started: the plate is at rest where it was. */
            c->src = FW_SRC_NONE;
            fw_traj_drop(&c->traj);
            fw_set_state(c, FW_STATE_STOPPING);
            return;
        }
    }
    fw_set_state(c, FW_STATE_STOPPING);
    /* Once a queued move has begun to blend in, the slides are on the sum of the two paths: the
     * stop must follow that path, for dropping the second move would send them back to the
     * first's at once.  Before, the path is the running move's alone. */
    const bool blending = c->src == FW_SRC_MOVE && c->has_next &&
                          c->tau >= (tse_real)c->blend_k0 / (tse_real)c->cfg.segment_hz;
    if (!blending)
        c->has_next = false;
    if (c->src == FW_SRC_MOVE && !blending && c->tau >= c->move.prof.T - c->move.prof.Ta) {
        /* Already on its final ramp, which stops within the limits: a second braking on top of
         * it would not. */
        return;
    }
    /* Moves and homing's joint move brake within the limit over their whole path (path_stop_time;
     * the slide speeds of a blend's two moves at most add); a trajectory's path is the host's,
     * still arriving, so its braking takes half the limit from the present speed. */
    c->stopping = true;
    c->stop_t = TSE_R(0.0);
    if (c->src == FW_SRC_JOINT)
        c->stop_T = path_stop_time(c, joint_v_peak(c), TSE_R(0.45));
    else if (c->src == FW_SRC_MOVE)
        c->stop_T = path_stop_time(c, c->move.v_peak + (blending ? c->next.v_peak : TSE_R(0.0)), TSE_R(0.4));
    else
        c->stop_T = traj_stop_time(c, TRAJ_STOP_SHARE);
}

void fw_fault_raise(fw_controller *c, fw_fault f)
{
    if (c->state == FW_STATE_FAULT || c->state == FW_STATE_ESTOP)
        return;
    if (c->state == FW_STATE_MOVING || c->state == FW_STATE_STOPPING || c->state == FW_STATE_HOMING) {
        if (c->pending_fault == FW_FAULT_NONE)
            c->pending_fault = f;
        fw_stop_motion(c);
        return;
    }
    latch_fault(c, f);
}

void fw_report_fault(fw_controller *c, fw_fault f)
{
    fw_fault_raise(c, f);
}

void fw_start_source(fw_controller *c, fw_source src)
{
    c->src = src;
    c->has_next = false;
    c->tau = TSE_R(0.0);
    c->segments_run = 0;
    c->stopping = false;
    fw_set_state(c, FW_STATE_MOVING);
}

/* Path time of the next segment: on the planner's grid exactly while running, so execution
 * solves the very poses validation solved; along the stop ramp when stopping.  *last is set on
 * the segment that ends the ramp or the source. */
static tse_real advance(fw_controller *c, tse_real end, bool *last)
{
    const tse_real dt = TSE_R(1.0) / (tse_real)c->cfg.segment_hz;
    *last = false;
    if (c->stopping) {
        c->stop_t += dt;
        tse_real rate = TSE_R(0.0);
        if (c->stop_t < c->stop_T) {
            const tse_real x = c->stop_t / c->stop_T;
            rate = TSE_R(1.0) - (x - tse_sin(TSE_R(2.0) * TSE_PI * x) / (TSE_R(2.0) * TSE_PI));
        } else {
            *last = true;
        }
        tse_real tau = c->tau + rate * dt;
        if (tau >= end) {
            tau = end;
            *last = true;
        }
        return tau;
    }
    tse_real tau = (tse_real)(c->segments_run + 1u) / (tse_real)c->cfg.segment_hz;
    if (tau >= end) {
        tau = end;
        *last = true;
    }
    return tau;
}

static void push_slides(fw_controller *c, const tse_real q[6])
{
    int32_t target[STEPGEN_AXES];
    for (int k = 0; k < 6; ++k) {
        target[k] = fw_to_steps(c, q[k]);
        c->q_prev[k] = c->q[k];
        c->q[k] = q[k];
    }
    stepgen_push(&c->sg, target);
    ++c->segments_run;
}

/* One control segment of a pose source: advance path time, solve, queue the setpoint. */
static void run_source(fw_controller *c)
{
    bool last;
    tse_real end;
    const tse_real t0 = (tse_real)c->blend_k0 / (tse_real)c->cfg.segment_hz;
    if (c->src == FW_SRC_MOVE)
        end = c->has_next ? t0 + c->next.prof.T : c->move.prof.T;
    else
        end = c->traj.closed ? (tse_real)fw_traj_end_us(&c->traj) * TSE_R(1e-6) : (tse_real)INFINITY;
    const uint32_t grid = c->segments_run + 1u;
    const tse_real tau = advance(c, end, &last);
    tse_real pose[6];
    bool inside = true;
    if (c->src == FW_SRC_TRAJ && !c->traj.closed && !c->stopping) {
        /* The host is falling behind: once less trajectory is queued than a stop needs, stop
         * along it while there is room, and latch the underrun. */
        const tse_real left = (tse_real)fw_traj_end_us(&c->traj) * TSE_R(1e-6) - c->tau;
        if (left <= TSE_R(0.5) * traj_stop_time(c, TRAJ_STOP_SHARE) + TSE_R(2.0) / (tse_real)c->cfg.segment_hz) {
            c->pending_fault = FW_FAULT_UNDERRUN;
            fw_stop_motion(c);
        }
    }
    if (c->src == FW_SRC_MOVE) {
        if (c->has_next)
            fw_move_blend_pose(&c->move, &c->next, c->blend_k0, &c->lim, tau, pose);
        else
            fw_move_pose(&c->move, tau, pose);
    } else {
        /* On the grid the time is exact in microseconds, as validation sampled it. */
        uint64_t tau_us = c->stopping ? (uint64_t)(tau * TSE_R(1e6) + TSE_R(0.5))
                                      : (uint64_t)grid * (1000000u / c->cfg.segment_hz);
        /* The last point exactly, when the path has reached it; a stop ramp that ends before it
         * ends where the ramp brought the slides. */
        if (last && c->traj.closed && tau >= end)
            tau_us = fw_traj_end_us(&c->traj);
        inside = fw_traj_pose(&c->traj, tau_us, pose);
    }
    if (!inside) {
        /* The stream ran dry before its last point: hold its newest point, and fault. */
        last = true;
        c->pending_fault = FW_FAULT_UNDERRUN;
        fw_traj_run_end(c, FW_TRAJ_END_FAULT, FW_FAULT_UNDERRUN);
    }
    tse_ik_result r;
    if (tse_ik(&c->geom, pose, c->q, &r) != TSE_OK) {
        /* Validation solved this path, so this is a defect: there is no pose to go on to. */
        c->src = FW_SRC_NONE;
        c->pending_fault = FW_FAULT_PLANNER;
        fw_traj_run_end(c, FW_TRAJ_END_FAULT, FW_FAULT_PLANNER);
        return;
    }
    for (int k = 0; k < 6; ++k)
        c->pose[k] = pose[k];
    push_slides(c, r.q);
    c->tau = tau;
    if (c->src == FW_SRC_MOVE && c->has_next && tau >= c->move.prof.T && !last) {
        /* The first move is over: the second goes on alone, on the same grid. */
        c->move = c->next;
        c->has_next = false;
        c->segments_run -= c->blend_k0;
        c->tau -= t0;
    }
    if (last) {
        c->src = FW_SRC_NONE;
        c->has_next = false;
    }
}

/* The joint-space move that ends homing: straight in slide space. */
static void run_joint(fw_controller *c)
{
    bool last;
    const tse_real tau = advance(c, c->joint.prof.T, &last);
    tse_real u, du, ddu;
    fw_profile_eval(&c->joint.prof, tau, &u, &du, &ddu);
    tse_real q[6];
    for (int k = 0; k < 6; ++k)
        q[k] = tau >= c->joint.prof.T ? c->joint.to[k] : c->joint.from[k] + u * (c->joint.to[k] - c->joint.from[k]);
    push_slides(c, q);
    c->tau = tau;
    if (last)
        c->src = FW_SRC_NONE;
}

/* What the switches say against what the controller believes: a high-end switch pressed, or, once
 * homed and outside homing, a low switch pressed clearly above its position or released clearly
 * below it (the step count and the switch disagree: lost steps, or a broken switch). */
static bool switches_disagree(const fw_controller *c, uint16_t pressed)
{
    if (pressed & 0x3F00u)
        return true;
    if (!c->homed || c->home.active)
        return false;
    int32_t pos[STEPGEN_AXES];
    stepgen_positions(&c->sg, pos);
    const int32_t tol = um_to_steps(&c->params, FW_HOME_SW_TOLERANCE_UM);
    for (int k = 0; k < 6; ++k) {
        const int32_t sw = fw_home_switch_steps(c, k);
        const bool on = (pressed >> k) & 1u;
        if ((on && pos[k] > sw + tol) || (!on && pos[k] < sw - tol))
            return true;
    }
    return false;
}

static void supervise(fw_controller *c)
{
    if (c->state == FW_STATE_BOOT)
        return;
    if (c->hal.inputs.estop(c->hal.inputs.ctx)) {
        if (c->state != FW_STATE_ESTOP)
            fw_estop(c);
        return;
    }
    const bool active = c->state == FW_STATE_IDLE || c->state == FW_STATE_MOVING ||
                        c->state == FW_STATE_STOPPING || c->state == FW_STATE_HOMING;
    if (!c->home.active && active && switches_disagree(c, c->hal.inputs.limits(c->hal.inputs.ctx))) {
        c->homed = false; /* the step count is not to be trusted any more */
        fw_fault_raise(c, FW_FAULT_LIMIT);
    }
    hal_can_state cs;
    c->hal.can.state(c->hal.can.ctx, &cs);
    /* A bus-off that recovered since the last look counts as much as one that lasts. */
    const bool went_bus_off = cs.bus_off_events != c->bus_off_seen;
    c->bus_off_seen = cs.bus_off_events;
    if ((cs.bus_off || went_bus_off) && c->state != FW_STATE_FAULT)
        fw_fault_raise(c, FW_FAULT_BUS_OFF);
    /* A segment the generator could not step in its time: the slides fell out of step with each
     * other and with the path, so the motion stops under control and the fault latches. */
    const uint32_t overruns = c->sg.overruns;
    if (overruns != c->overruns_seen) {
        c->overruns_seen = overruns;
        fw_fault_raise(c, FW_FAULT_STEP_OVERRUN);
    }
    const uint32_t wd = (uint32_t)c->params.v[FP_WATCHDOG_MS];
    if (wd > 0 && c->drives_on && now_us(c) - c->last_heartbeat_us > (uint64_t)wd * 1000u)
        fw_fault_raise(c, FW_FAULT_WATCHDOG);
}

void fw_control_tick(fw_controller *c)
{
    fw_estop_complete(c);
    supervise(c);
    if (c->state == FW_STATE_ESTOP || c->state == FW_STATE_FAULT || c->state == FW_STATE_BOOT)
        return;
    if (c->home.active && c->src == FW_SRC_NONE) {
        fw_homing_tick(c);
        return;
    }
    /* A trajectory whose queue is still filling holds the plate at rest. */
    const bool priming = c->src == FW_SRC_TRAJ && fw_traj_run_priming(c);
    while (!priming && c->src != FW_SRC_NONE && stepgen_queued(&c->sg) < QUEUE_AHEAD) {
        if (c->src == FW_SRC_JOINT)
            run_joint(c);
        else
            run_source(c);
    }
    if (c->src != FW_SRC_NONE || !stepgen_idle(&c->sg))
        return;
    /* The source is exhausted and the slides are at their last setpoint. */
    if (c->home.active) {
        fw_homing_tick(c); /* the joint move to the home pose ended */
        return;
    }
    if (c->state == FW_STATE_MOVING || c->state == FW_STATE_STOPPING) {
        /* At rest: what a stop ramp left of the trajectory is not for running any more. */
        c->stopping = false;
        fw_traj_run_end_pending(c, FW_TRAJ_END_DONE);
        fw_traj_drop(&c->traj);
        if (c->pending_fault != FW_FAULT_NONE)
            latch_fault(c, c->pending_fault);
        else
            fw_set_state(c, FW_STATE_IDLE);
    }
}

static void send_status(fw_controller *c)
{
    uint8_t flags = 0;
    if (c->homed)
        flags |= 1u;
    if (c->drives_on)
        flags |= 2u;
    if (c->hal.inputs.estop(c->hal.inputs.ctx))
        flags |= 4u;
    if (switches_disagree(c, c->hal.inputs.limits(c->hal.inputs.ctx)))
        flags |= 8u;
    hal_can_state cs;
    c->hal.can.state(c->hal.can.ctx, &cs);
    if (cs.error_passive)
        flags |= 16u;
    const int32_t v[7] = {c->state, c->fault, flags, (int32_t)fw_traj_depth(&c->traj),
                          (int32_t)fw_traj_free(&c->traj), c->last_seq, c->counter++};
    fw_send(c, PM_STATUS, v);
}

/* A slide position in the wire's nanometres.  The stroke may reach 5 m, beyond what an i32 of
 * nanometres holds (2.147 m): past it the field's end is sent, not an undefined conversion. */
static int32_t wire_nm(tse_real s)
{
    const tse_real nm = s * TSE_R(1e9);
    if (nm >= TSE_R(2147483647.0))
        return INT32_MAX;
    if (nm <= TSE_R(-2147483648.0))
        return INT32_MIN;
    return (int32_t)nm;
}

static void send_telemetry(fw_controller *c)
{
    int32_t steps[6];
    stepgen_positions(&c->sg, steps);
    tse_real q[6];
    const tse_real spm = (tse_real)c->params.v[FP_STEPS_PER_M];
    for (int k = 0; k < 6; ++k)
        q[k] = (tse_real)steps[k] / spm;
    for (int k = 0; k < 3; ++k) {
        const int32_t v[2] = {wire_nm(q[2 * k]), wire_nm(q[2 * k + 1])};
        fw_send(c, (proto_msg)(PM_SLIDES_A + k), v);
    }
    if (!c->homed)
        return; /* no zero, no pose */
    tse_fk_result fk;
    if (tse_fk(&c->geom, q, c->pose_known ? c->pose : c->geom.home_pose, &fk) != TSE_OK)
        return;
    for (int k = 0; k < 3; ++k) {
        const int32_t v[2] = {(int32_t)(fk.pose[2 * k] * TSE_R(1e6)), (int32_t)(fk.pose[2 * k + 1] * TSE_R(1e6))};
        fw_send(c, (proto_msg)(PM_FK_A + k), v);
    }
}

void fw_poll(fw_controller *c)
{
    fw_estop_complete(c);
    /* How a trajectory ended goes out before any row of the next is taken. */
    fw_traj_run_report(c);
    hal_can_frame f;
    while (c->hal.can.receive(c->hal.can.ctx, &f) == 1)
        fw_handle_frame(c, &f);
    fw_traj_run_report(c);
    const uint64_t t = now_us(c);
    if (t >= c->next_status_us) {
        send_status(c);
        c->next_status_us = t + (uint64_t)c->params.v[FP_STATUS_MS] * 1000u;
    }
    const uint32_t tel = (uint32_t)c->params.v[FP_TELEMETRY_MS];
    if (tel > 0 && t >= c->next_telemetry_us) {
        send_telemetry(c);
        c->next_telemetry_us = t + (uint64_t)tel * 1000u;
    }
}
