#include "adopt.h"

#include "fw/limits.h"

fw_param_rule fw_params_prepare(const fw_controller *c, const fw_param_set *s, fw_prepared_params *p)
{
    const fw_param_rule rule = fw_params_judge_config(s, c->cfg.step_hz, c->cfg.segment_hz).rule;
    if (rule != FW_RULE_NONE)
        return rule;
    if (fw_limits_from_params(s, c->cfg.step_hz, c->cfg.segment_hz, &p->g, &p->lim) != 0 ||
        fw_stepgen_config_from_params(s, c->cfg.step_hz, c->cfg.segment_hz, &p->sc) != FW_RULE_NONE)
        return FW_RULE_GEOMETRY; /* what the judge passed, these take: not reached */
    p->s = *s;
    return FW_RULE_NONE;
}

fw_param_rule fw_params_adopt(fw_controller *c, const fw_prepared_params *p)
{
    fw_tick *t = &c->tick;
    const fw_param_set *s = &p->s;
    int32_t pos[STEPGEN_AXES];
    stepgen_positions(&c->sg, pos);
    if (!stepgen_idle(&c->sg) || stepgen_init(&c->sg, &p->sc, pos) != 0)
        return FW_RULE_NOT_AT_REST; /* parameters change only at rest */
    t->overruns_seen = 0; /* the fresh generator counts from zero */
    /* A fresh generator is not halted: an e-stop before it asked for a halt that must last until
     * the request is completed (the generator is idle, so no step came in between). */
    if (atomic_load(&c->sh.estop_request))
        stepgen_halt(&c->sg);
    /* A fresh generator assumes its direction mask: make the pins agree with it. */
    c->hal.stepper.set_dir(c->hal.stepper.ctx, c->sg.forward_mask);
    if (c->hal.stepper.timing)
        c->hal.stepper.timing(c->hal.stepper.ctx, (uint32_t)s->v[FP_STEP_PULSE_NS], (uint32_t)s->v[FP_DIR_SETUP_NS]);
    /* The zero was set against the old switch positions and step size. */
    bool rezero = s->v[FP_STEPS_PER_M] != t->params.v[FP_STEPS_PER_M];
    for (int k = 0; k < 6; ++k)
        rezero = rezero || s->v[FP_HOME_SW_1 + k] != t->params.v[FP_HOME_SW_1 + k];
    /* A new geometry or stroke: the pose the slides hold, and whether they are inside the stroke,
     * are other than what was known; homing again establishes both (the margins only judge
     * future paths, so they keep it). */
    for (int id = FP_L; id <= FP_S_MAX; ++id)
        rezero = rezero || s->v[id] != t->params.v[id];
    if (rezero) {
        t->homed = false;
        t->pose_known = false;
    }
    t->params = *s;
    t->geom = p->g;
    t->lim = p->lim;
    return FW_RULE_NONE;
}
