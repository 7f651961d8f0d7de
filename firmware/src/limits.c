#include "fw/limits.h"

#include <string.h>

#include "fw/proto_wire.h"

/* The STEP pulse against the step interrupt period T = 1e9 / step_hz ns: it must end within the
 * period it rose in (the step generator changes DIR only at a tick, so DIR never changes under a
 * high STEP, and a board that ends the pulse from its step timer has a compare within the period),
 * and the same slide's next rising edge, at least min_step_interval periods later, must leave a low
 * time at least as long as the high time. */
static fw_param_rule pulse_rule(uint32_t pulse_ns, uint32_t step_hz, uint32_t interval)
{
    const uint64_t high = (uint64_t)pulse_ns * step_hz; /* in units of 1e-9 periods */
    if (high >= 1000000000u)
        return FW_RULE_PULSE_PERIOD;
    if (2u * high > (uint64_t)interval * 1000000000u)
        return FW_RULE_PULSE_LOW;
    return FW_RULE_NONE;
}

bool fw_rates_run(fw_rates r)
{
    const proto_wire_field *info = proto_wire[PM_INFO].fields; /* major, minor, patch, step_hz, segment_hz */
    return r.segment_hz != 0 && 1000000u % r.segment_hz == 0 && r.step_hz % r.segment_hz == 0 &&
           r.step_hz <= (uint32_t)info[3].max && r.segment_hz <= (uint32_t)info[4].max;
}

uint32_t fw_step_interval_ticks(int32_t rate, uint32_t step_hz)
{
    if (rate <= 0)
        return UINT32_MAX;
    const uint32_t interval = (uint32_t)(((uint64_t)step_hz + (uint32_t)rate - 1u) / (uint32_t)rate);
    return interval == 0 ? 1u : interval;
}

uint32_t fw_dir_setup_ticks(uint32_t dir_ns, uint32_t step_hz)
{
    /* DIR and STEP are both written inside step interrupts, at offsets that vary with the
     * interrupt's work (a segment's first tick does more), so a set-up of exactly the asked ticks
     * could come out a fraction of a microsecond short on the board: one more.  No set-up asked:
     * the generator's own minimum of one. */
    if (dir_ns == 0)
        return 1u;
    const uint64_t setup = ((uint64_t)dir_ns * step_hz + 999999999u) / 1000000000u + 1u;
    return setup > UINT32_MAX ? UINT32_MAX : (uint32_t)setup;
}

fw_param_rule fw_stepgen_config_from_params(const fw_param_set *s, uint32_t step_hz, uint32_t segment_hz,
                                            stepgen_config *sc)
{
    const int32_t rate = s->v[FP_STEP_RATE_MAX];
    if (segment_hz == 0 || step_hz == 0 || step_hz % segment_hz != 0 || step_hz / segment_hz > UINT32_MAX / 4u)
        return FW_RULE_CONFIG; /* or the generator's arithmetic would overflow */
    if (rate <= 0)
        return FW_RULE_RANGE;
    const uint32_t interval = fw_step_interval_ticks(rate, step_hz);
    const fw_param_rule pulse = pulse_rule((uint32_t)s->v[FP_STEP_PULSE_NS], step_hz, interval);
    if (pulse != FW_RULE_NONE)
        return pulse;
    const uint32_t setup = fw_dir_setup_ticks((uint32_t)s->v[FP_DIR_SETUP_NS], step_hz);
    const uint32_t per_segment = step_hz / segment_hz;
    /* No room for a step in a segment that changes direction (after the set-up, less than one
     * step interval left: the slides' speed limit would be zero). */
    if (setup >= per_segment || (per_segment - setup) / interval == 0)
        return FW_RULE_DIR_SETUP_ROOM;
    sc->ticks_per_segment = per_segment;
    sc->dir_setup_ticks = setup;
    sc->min_step_interval = interval;
    return FW_RULE_NONE;
}

fw_param_fault fw_params_judge_config(const fw_param_set *s, uint32_t step_hz, uint32_t segment_hz)
{
    fw_param_fault f = fw_params_judge(s);
    if (f.rule != FW_RULE_NONE)
        return f;
    stepgen_config sc;
    f.rule = fw_stepgen_config_from_params(s, step_hz, segment_hz, &sc);
    f.id = f.rule == FW_RULE_PULSE_PERIOD || f.rule == FW_RULE_PULSE_LOW ? FP_STEP_PULSE_NS
           : f.rule == FW_RULE_DIR_SETUP_ROOM                          ? FP_DIR_SETUP_NS
                                                                        : -1;
    return f;
}

int fw_speed_limit_from_params(const fw_param_set *s, uint32_t step_hz, uint32_t segment_hz, fw_speed_limit *v)
{
    if (fw_stepgen_config_from_params(s, step_hz, segment_hz, &v->sc) != FW_RULE_NONE)
        return -1;
    /* The step generator's ceiling, with room for the rounding of each segment to whole steps; a
     * segment that reverses loses its direction set-up. */
    v->segment_steps = stepgen_capacity(&v->sc, true);
    v->by_param = (tse_real)s->v[FP_SLIDE_VMAX] * (TSE_R(1.0) / PROTO_UM_PER_M);
    v->by_steps = FW_STEP_RATE_MARGIN * (tse_real)v->segment_steps * (tse_real)segment_hz /
                  (tse_real)s->v[FP_STEPS_PER_M];
    v->by = v->by_steps < v->by_param ? FW_LIMIT_STEP_GENERATOR : FW_LIMIT_SLIDE_VMAX;
    v->vmax = v->by == FW_LIMIT_STEP_GENERATOR ? v->by_steps : v->by_param;
    return 0;
}

int fw_limits_from_params(const fw_param_set *s, uint32_t step_hz, uint32_t segment_hz,
                          tse_geometry *g, fw_limits *lim)
{
    tse_params kp;
    fw_speed_limit v;
    if (fw_params_judge_config(s, step_hz, segment_hz).rule != FW_RULE_NONE ||
        fw_speed_limit_from_params(s, step_hz, segment_hz, &v) != 0)
        return -1;
    fw_params_kinematics(s, &kp);
    /* The geometry last: tse_geometry_init leaves it untouched when it refuses, so a refused set
     * changes neither output. */
    if (tse_geometry_init(g, &kp) != TSE_PARAM_OK)
        return -1;
    const tse_real micro = TSE_R(1e-6);
    memset(lim, 0, sizeof *lim); /* padding too: a copy compares equal byte for byte */
    lim->slide_vmax = v.vmax;
    lim->vmax_by = v.by;
    lim->slide_amax = (tse_real)s->v[FP_SLIDE_AMAX] * micro;
    lim->plate_vmax = (tse_real)s->v[FP_PLATE_VMAX] * micro;
    lim->plate_amax = (tse_real)s->v[FP_PLATE_AMAX] * micro;
    lim->plate_jmax = (tse_real)s->v[FP_PLATE_JMAX] * micro;
    lim->plate_wmax = (tse_real)s->v[FP_PLATE_WMAX] * micro;
    lim->plate_dwmax = (tse_real)s->v[FP_PLATE_DWMAX] * micro;
    lim->segment_hz = (tse_real)segment_hz;
    return 0;
}

tse_real fw_slide_jmax(const fw_limits *lim)
{
    return lim->slide_amax * lim->plate_jmax / lim->plate_amax;
}
