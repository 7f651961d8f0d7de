/* Homing: every slide seeks its low limit switch, brakes, creeps back until the switch releases
 * (that edge is the slide's zero: the switch sits at s_min), then all six go to the symmetric
 * home configuration in a joint-space move.  Joint speeds ramp within the slide acceleration
 * limit throughout, so a stop or fault can bring homing to rest at any moment. */
#include "fw/controller_internal.h"

/* The release creep runs at this fraction of the homing speed, so that the slide moves less than
 * a step per control tick and the switch edge (the zero) is found to within one step: a step of
 * slide error is several micrometres at the plate. */
#define CREEP_FRACTION TSE_R(0.015625) /* 1/64 */
/* Margin of travel beyond the full stroke before a missing switch is declared. */
#define SEEK_MARGIN TSE_R(0.05)

void fw_homing_start(fw_controller *c)
{
    fw_homing *h = &c->home;
    h->active = true;
    h->abort = false;
    h->phase = HOME_SEEK;
    h->hit = 0;
    h->latched = 0;
    stepgen_positions(&c->sg, h->start_steps);
    for (int k = 0; k < 6; ++k) {
        h->v[k] = TSE_R(0.0);
        h->s[k] = TSE_R(0.0);
        h->offset[k] = TSE_R(0.0);
        h->released[k] = TSE_R(0.0);
    }
    c->homed = false;
    c->pose_known = false;
    c->src = FW_SRC_NONE;
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

static void finish(fw_controller *c, bool homed)
{
    c->home.active = false;
    c->homed = homed;
    if (c->pending_fault != FW_FAULT_NONE) {
        const fw_fault f = c->pending_fault;
        c->pending_fault = FW_FAULT_NONE;
        c->state = FW_STATE_IDLE; /* so that the fault latches rather than stopping again */
        fw_fault_raise(c, f);
        return;
    }
    fw_set_state(c, FW_STATE_IDLE);
}

static void start_joint_move(fw_controller *c)
{
    fw_homing *h = &c->home;
    int32_t now[6];
    tse_real longest = TSE_R(0.0);
    for (int k = 0; k < 6; ++k) {
        c->joint.from[k] = h->s[k] + h->offset[k];
        c->joint.to[k] = c->geom.home_s;
        now[k] = fw_to_steps(c, c->joint.from[k]);
        c->q[k] = c->q_prev[k] = c->joint.from[k];
        const tse_real d = tse_fabs(c->joint.to[k] - c->joint.from[k]);
        if (d > longest)
            longest = d;
    }
    stepgen_set_position(&c->sg, now); /* the zero: from here on steps count from s = 0 */
    const tse_real n = longest > TSE_R(0.0) ? longest : TSE_R(1.0);
    const tse_real jerk = c->lim.slide_amax * c->lim.plate_jmax / c->lim.plate_amax;
    fw_profile_plan(&c->joint.prof, longest > TSE_R(0.0) ? TSE_R(1.0) : TSE_R(0.0),
                    TSE_R(0.9) * c->lim.slide_vmax / n, TSE_R(0.9) * c->lim.slide_amax / n, jerk / n,
                    TSE_R(0.0));
    h->phase = HOME_TO_POSE;
    c->tau = TSE_R(0.0);
    c->segments_run = 0;
    c->stopping = false;
    c->src = FW_SRC_JOINT;
}

void fw_homing_tick(fw_controller *c)
{
    fw_homing *h = &c->home;
    if (h->phase == HOME_TO_POSE) {
        /* The joint move has ended (fw_control_tick runs it as a source). */
        if (h->abort) {
            finish(c, false);
            return;
        }
        for (int k = 0; k < 6; ++k)
            c->pose[k] = c->geom.home_pose[k];
        c->pose_known = true;
        finish(c, true);
        return;
    }
    if (stepgen_queued(&c->sg) >= 2u)
        return;

    const tse_real dt = TSE_R(1.0) / (tse_real)c->cfg.segment_hz;
    const tse_real dv = TSE_R(0.9) * c->lim.slide_amax * dt;
    const tse_real v_home = (tse_real)c->params.v[FP_HOMING_SPEED] * TSE_R(1e-6);
    const tse_real stroke = c->geom.p.s_max - c->geom.p.s_min;
    const uint16_t pressed = c->hal.inputs.limits(c->hal.inputs.ctx);
    bool moving = false;
    int32_t target[6];
    for (int k = 0; k < 6; ++k) {
        const bool on = (pressed >> k) & 1u;
        tse_real want = TSE_R(0.0);
        if (!h->abort) {
            if (h->phase == HOME_SEEK) {
                if (on)
                    h->hit |= (uint8_t)(1u << k);
                if (!((h->hit >> k) & 1u))
                    want = -v_home;
                if (-h->s[k] > stroke + SEEK_MARGIN) {
                    c->pending_fault = FW_FAULT_HOMING;
                    h->abort = true;
                }
            } else if (h->phase == HOME_RELEASE && !((h->latched >> k) & 1u)) {
                if (!on) {
                    /* The edge: this travel is s = s_min. */
                    h->latched |= (uint8_t)(1u << k);
                    h->offset[k] = c->geom.p.s_min - h->s[k];
                } else {
                    want = CREEP_FRACTION * v_home;
                    if (h->s[k] - h->released[k] > SEEK_MARGIN) {
                        c->pending_fault = FW_FAULT_HOMING;
                        h->abort = true;
                    }
                }
            }
        }
        h->v[k] = approach(h->v[k], h->abort ? TSE_R(0.0) : want, dv);
        h->s[k] += h->v[k] * dt;
        if (h->v[k] != TSE_R(0.0))
            moving = true;
        target[k] = h->start_steps[k] + fw_to_steps(c, h->s[k]);
    }
    if (moving) {
        stepgen_push(&c->sg, target);
        return;
    }
    if (!stepgen_idle(&c->sg))
        return;
    /* At rest: on to the next phase. */
    if (h->abort) {
        finish(c, false);
    } else if (h->phase == HOME_SEEK && h->hit == 0x3Fu) {
        h->phase = HOME_RELEASE;
        for (int k = 0; k < 6; ++k)
            h->released[k] = h->s[k];
    } else if (h->phase == HOME_RELEASE && h->latched == 0x3Fu) {
        start_joint_move(c);
    }
}
