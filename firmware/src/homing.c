/* Homing: every slide finds the release edge of its low switch on its own, then all six go to the
 * symmetric home configuration in a joint-space move.
 *
 * The switch of slide k is pressed at and below home_sw_k and released above it, so a slide below
 * its switch sees it pressed.  Each slide:
 *   LEAVE   (only if it starts pressed) up at the homing speed until the switch releases, on for
 *           homing_backoff, then brakes;
 *   SEEK    down at the homing speed until the switch is pressed, then brakes;
 *   RELEASE up at the creep speed until the switch releases: that edge, the first step above the
 *           last pressed one, is s = home_sw_k plus one step;
 *   DONE.
 * So homing takes the distances at the homing speed; only the braking distance and the switch's
 * hysteresis are crept.  At rest on the edges, the zero is set and the thread checks the joint
 * move's path (a quarter of a million instructions on the board: not in the control tick) before
 * it starts.  Joint speeds ramp within the slide acceleration limit throughout, so a
 * stop or fault can bring homing to rest at any moment. */
#include "homing.h"

#include <stdatomic.h>

#include "fw/joint_path.h"
#include "steps.h"

/* The release creep runs at this fraction of the homing speed, and at most half a step per control
 * tick: the steps emitted are read once per tick, so with less than one step between two reads the
 * step at which the switch released is known exactly (a step of slide error is several
 * micrometres at the plate). */
#define CREEP_FRACTION TSE_R(0.015625) /* 1/64 */
/* Travel beyond the full stroke before a missing switch (seeking) or a switch that never releases
 * (leaving) is declared. */
#define SEEK_MARGIN TSE_R(0.05)
/* Creep beyond the braking distance before a release that never comes is declared: a switch's
 * hysteresis is well under a millimetre. */
#define RELEASE_MARGIN TSE_R(0.005)
/* Of the acceleration limit, what the homing ramps use. */
#define ACCEL_SHARE TSE_R(0.9)

void fw_homing_start(fw_controller *c)
{
    fw_homing *h = &c->tick.home;
    h->active = true;
    h->abort = false;
    h->phase = HOME_SWITCHES;
    h->released = 0;
    h->hit = 0;
    stepgen_positions(&c->sg, h->start_steps);
    const uint16_t pressed = c->hal.inputs.limits(c->hal.inputs.ctx);
    for (int k = 0; k < 6; ++k) {
        h->axis[k] = (uint8_t)(((pressed >> k) & 1u) ? HOME_AXIS_LEAVE : HOME_AXIS_SEEK);
        h->v[k] = TSE_R(0.0);
        h->s[k] = TSE_R(0.0);
        h->mark[k] = TSE_R(0.0);
        h->edge_steps[k] = 0;
    }
    c->tick.homed = false;
    c->tick.pose_known = false;
    c->tick.src = FW_SRC_NONE;
    fw_set_state(c, FW_STATE_HOMING);
}

static tse_real approach(tse_real v, tse_real target, tse_real dv)
{
    if (target > v + dv)
        return v + dv;
    if (target < v - dv)
        return v - dv;
    return target;
}

static fw_homing_outcome finish(fw_controller *c, bool homed)
{
    c->tick.home.active = false;
    c->tick.homed = homed;
    return FW_HOMING_ENDED;
}

static void homing_fault(fw_controller *c)
{
    c->tick.pending_fault = FW_FAULT_HOMING;
    c->tick.home.abort = true;
}

/* At rest on the switches' edges: the zero, and the joint move's ends; its path goes to the thread
 * for its check (fw_homing_check_path). */
static void await_path_check(fw_controller *c)
{
    fw_homing *h = &c->tick.home;
    int32_t now[6];
    stepgen_positions(&c->sg, now); /* at rest: every pushed step is out */
    const tse_real spm = (tse_real)c->tick.params.v[FP_STEPS_PER_M];
    for (int k = 0; k < 6; ++k) {
        /* The edge step is one above home_sw_k; what came after it counts on from there. */
        now[k] = fw_switch_steps(&c->tick.params, k) + 1 + (now[k] - h->edge_steps[k]);
        c->tick.joint.from[k] = (tse_real)now[k] / spm;
        c->tick.joint.to[k] = c->tick.geom.home_s;
        c->tick.q[k] = c->tick.q_prev[k] = c->tick.joint.from[k];
    }
    stepgen_set_position(&c->sg, now); /* the zero: from here on steps count from s = 0 */
    h->phase = HOME_PATH_CHECK;
    h->path_ask = 0;
}

/* Asks the thread to check the joint move's path, once its answer to any earlier ask is in (a
 * homing stopped while its check ran leaves one behind). */
static void ask_path_check(fw_controller *c)
{
    fw_shared *s = &c->sh;
    const uint32_t asked = atomic_load_explicit(&s->path_asked, memory_order_relaxed);
    if (atomic_load_explicit(&s->path_answered, memory_order_acquire) != asked)
        return;
    for (int k = 0; k < 6; ++k)
        s->path_from[k] = c->tick.joint.from[k];
    c->tick.home.path_ask = asked + 1u ? asked + 1u : 1u;
    atomic_store_explicit(&s->path_asked, c->tick.home.path_ask, memory_order_release);
}

void fw_homing_check_path(fw_controller *c)
{
    fw_shared *s = &c->sh;
    const uint32_t asked = atomic_load_explicit(&s->path_asked, memory_order_acquire);
    if (asked == atomic_load_explicit(&s->path_answered, memory_order_relaxed))
        return;
    /* Validated as any move is before its first step (the parameter check has checked it from the
     * switches themselves, fw_params_judge), with the thread's copy of the tick's parameters. */
    tse_real where;
    int scissor;
    s->path_ok = fw_joint_path_check(&c->th.geom, s->path_from, &where, &scissor) == TSE_OK;
    atomic_store_explicit(&s->path_answered, asked, memory_order_release);
}

/* The joint move from the switches' edges to the home pose, its path checked. */
static void start_joint_move(fw_controller *c)
{
    tse_real longest = TSE_R(0.0);
    for (int k = 0; k < 6; ++k) {
        const tse_real d = tse_fabs(c->tick.joint.to[k] - c->tick.joint.from[k]);
        if (d > longest)
            longest = d;
    }
    const tse_real n = longest > TSE_R(0.0) ? longest : TSE_R(1.0);
    const tse_real jerk = fw_slide_jmax(&c->tick.lim);
    fw_profile_plan(&c->tick.joint.prof, longest > TSE_R(0.0) ? TSE_R(1.0) : TSE_R(0.0),
                    TSE_R(0.9) * c->tick.lim.slide_vmax / n, TSE_R(0.9) * c->tick.lim.slide_amax / n, jerk / n,
                    TSE_R(0.0));
    c->tick.home.phase = HOME_TO_POSE;
    c->tick.tau = TSE_R(0.0);
    c->tick.segments_run = 0;
    c->tick.stopping = false;
    c->tick.src = FW_SRC_JOINT;
}

/* HOME_PATH_CHECK: asked, then waiting for the answer; a stop or a fault meanwhile ends homing. */
static fw_homing_outcome path_check_tick(fw_controller *c)
{
    fw_homing *h = &c->tick.home;
    if (h->abort)
        return finish(c, false);
    if (h->path_ask == 0) {
        ask_path_check(c);
        return FW_HOMING_GOING;
    }
    if (atomic_load_explicit(&c->sh.path_answered, memory_order_acquire) != h->path_ask)
        return FW_HOMING_GOING;
    if (!c->sh.path_ok) {
        c->tick.pending_fault = FW_FAULT_HOMING;
        return finish(c, false);
    }
    start_joint_move(c);
    return FW_HOMING_GOING;
}

typedef struct {
    tse_real v_home, creep, backoff, brake, stroke;
} home_speeds;

/* The speed slide k asks for on this tick, with its edges (switch changes) taken; a fault aborts
 * homing.  on/high: its low and high switch; pos: steps emitted, read after the switches. */
static tse_real axis_want(fw_controller *c, const home_speeds *hs, int k, bool on, bool high, int32_t pos)
{
    fw_homing *h = &c->tick.home;
    const uint8_t bit = (uint8_t)(1u << k);
    switch ((fw_home_axis)h->axis[k]) {
    case HOME_AXIS_LEAVE:
        if (!(h->released & bit)) {
            if (!on) {
                h->released |= bit;
                h->mark[k] = h->s[k];
            } else if (high || h->s[k] > hs->stroke + SEEK_MARGIN) {
                homing_fault(c); /* the switch does not release */
                return TSE_R(0.0);
            }
        }
        if (!(h->released & bit) || h->s[k] - h->mark[k] < hs->backoff)
            return hs->v_home;
        return TSE_R(0.0);
    case HOME_AXIS_SEEK:
        if (on)
            h->hit |= bit;
        if (h->mark[k] - h->s[k] > hs->stroke + SEEK_MARGIN) {
            homing_fault(c); /* no switch within the stroke */
            return TSE_R(0.0);
        }
        return (h->hit & bit) ? TSE_R(0.0) : -hs->v_home;
    case HOME_AXIS_RELEASE:
        if (!on) {
            h->edge_steps[k] = pos;
            h->axis[k] = HOME_AXIS_DONE;
            return TSE_R(0.0);
        }
        if (h->s[k] - h->mark[k] > hs->brake + RELEASE_MARGIN)
            homing_fault(c);
        return hs->creep;
    case HOME_AXIS_DONE:
        break;
    }
    return TSE_R(0.0);
}

/* Slide k has come to rest (asked speed and speed both zero): the next phase. */
static void axis_at_rest(fw_controller *c, int k, bool on)
{
    fw_homing *h = &c->tick.home;
    const uint8_t bit = (uint8_t)(1u << k);
    if (h->axis[k] == HOME_AXIS_LEAVE && (h->released & bit)) {
        if (on) {
            h->released &= (uint8_t)~bit; /* a glitch, not the release: go on leaving */
            return;
        }
        h->axis[k] = HOME_AXIS_SEEK;
        h->mark[k] = h->s[k];
    } else if (h->axis[k] == HOME_AXIS_SEEK && (h->hit & bit)) {
        if (!on) {
            h->hit &= (uint8_t)~bit; /* a glitch, not the press: go on seeking */
            return;
        }
        h->axis[k] = HOME_AXIS_RELEASE;
        h->mark[k] = h->s[k];
    }
}

fw_homing_outcome fw_homing_tick(fw_controller *c)
{
    fw_homing *h = &c->tick.home;
    if (h->phase == HOME_TO_POSE) {
        /* The joint move has ended (motion.c runs it as a source). */
        if (h->abort)
            return finish(c, false);
        for (int k = 0; k < 6; ++k)
            c->tick.pose[k] = c->tick.geom.home_pose[k];
        c->tick.pose_known = true;
        return finish(c, true);
    }
    if (h->phase == HOME_PATH_CHECK)
        return path_check_tick(c);
    if (stepgen_queued(&c->sg) >= 2u)
        return FW_HOMING_GOING;

    const tse_real dt = TSE_R(1.0) / (tse_real)c->cfg.segment_hz;
    const tse_real accel = ACCEL_SHARE * c->tick.lim.slide_amax;
    const tse_real dv = accel * dt;
    const tse_real spm = (tse_real)c->tick.params.v[FP_STEPS_PER_M];
    home_speeds hs;
    hs.v_home = (tse_real)c->tick.params.v[FP_HOMING_SPEED] * (TSE_R(1.0) / PROTO_UM_PER_M);
    /* Homing moves slides like any motion: within the slide speed limit and what the step
     * generator can step (both in lim.slide_vmax), however fast homing_speed asks. */
    if (hs.v_home > c->tick.lim.slide_vmax)
        hs.v_home = c->tick.lim.slide_vmax;
    hs.creep = CREEP_FRACTION * hs.v_home;
    const tse_real half_step_per_tick = TSE_R(0.5) * (tse_real)c->cfg.segment_hz / spm;
    if (hs.creep > half_step_per_tick)
        hs.creep = half_step_per_tick;
    hs.backoff = (tse_real)c->tick.params.v[FP_HOMING_BACKOFF] * (TSE_R(1.0) / PROTO_UM_PER_M);
    /* Braking from the homing speed covers v^2 / 2a, plus a tick at full speed per ramp step. */
    hs.brake = hs.v_home * hs.v_home / (TSE_R(2.0) * accel) + hs.v_home * dt;
    hs.stroke = c->tick.geom.p.s_max - c->tick.geom.p.s_min;
    const uint16_t pressed = c->hal.inputs.limits(c->hal.inputs.ctx);
    int32_t pos[6];
    stepgen_positions(&c->sg, pos); /* after the switches: a release seen is in these steps */
    bool moving = false, done = true;
    int32_t target[6];
    for (int k = 0; k < 6; ++k) {
        const bool on = (pressed >> k) & 1u, high = (pressed >> (8 + k)) & 1u;
        const tse_real want = h->abort ? TSE_R(0.0) : axis_want(c, &hs, k, on, high, pos[k]);
        h->v[k] = approach(h->v[k], h->abort ? TSE_R(0.0) : want, dv);
        h->s[k] += h->v[k] * dt;
        if (h->v[k] != TSE_R(0.0))
            moving = true;
        else if (want == TSE_R(0.0) && !h->abort)
            axis_at_rest(c, k, on);
        if (h->axis[k] != HOME_AXIS_DONE)
            done = false;
        target[k] = h->start_steps[k] + fw_steps_of(&c->tick.params, h->s[k]);
    }
    if (moving) {
        stepgen_push(&c->sg, target);
        return FW_HOMING_GOING;
    }
    if (!stepgen_idle(&c->sg))
        return FW_HOMING_GOING;
    /* At rest: on to the home pose, or the end. */
    if (h->abort)
        return finish(c, false);
    if (done)
        await_path_check(c);
    return FW_HOMING_GOING;
}
