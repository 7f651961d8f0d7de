#include "fw/limits.h"

/* The STEP pulse against the step interrupt period T = 1e9 / step_hz ns: it must end within the
 * period it rose in (the step generator changes DIR only at a tick, so DIR never changes under a
 * high STEP, and a board that ends the pulse from its step timer has a compare within the period),
 * and the same slide's next rising edge, at least min_step_interval periods later, must leave a low
 * time at least as long as the high time. */
static int pulse_fits(uint32_t pulse_ns, uint32_t step_hz, uint32_t interval)
{
    const uint64_t high = (uint64_t)pulse_ns * step_hz; /* in units of 1e-9 periods */
    return high < 1000000000u && 2u * high <= (uint64_t)interval * 1000000000u;
}

int fw_stepgen_config_from_params(const fw_param_set *s, uint32_t step_hz, uint32_t segment_hz,
                                  stepgen_config *sc)
{
    const int32_t rate = s->v[FP_STEP_RATE_MAX];
    if (segment_hz == 0 || step_hz == 0 || step_hz % segment_hz != 0 || rate <= 0)
        return -1;
    /* Two steps of one slide at least step_hz / step_rate_max ticks apart. */
    uint32_t interval = (uint32_t)(((uint64_t)step_hz + (uint32_t)rate - 1u) / (uint32_t)rate);
    if (interval == 0)
        interval = 1;
    const uint32_t pulse_ns = (uint32_t)s->v[FP_STEP_PULSE_NS], dir_ns = (uint32_t)s->v[FP_DIR_SETUP_NS];
    if (!pulse_fits(pulse_ns, step_hz, interval))
        return -1;
    /* DIR set-up in whole ticks, rounded up, plus one: DIR and STEP are both written inside step
     * interrupts, at offsets that vary with the interrupt's work (a segment's first tick does
     * more), so a set-up of exactly the asked ticks could come out a fraction of a microsecond
     * short on the board.  No set-up asked: the generator's own minimum of one. */
    uint64_t setup = ((uint64_t)dir_ns * step_hz + 999999999u) / 1000000000u;
    setup = dir_ns == 0 ? 1u : setup + 1u;
    const uint32_t per_segment = step_hz / segment_hz;
    /* No room for a step in a segment that changes direction (after the set-up, less than one
     * step interval left: the slides' speed limit would be zero); or the generator's arithmetic
     * would overflow. */
    if (setup >= per_segment || (per_segment - setup) / interval == 0 || per_segment > UINT32_MAX / 4u)
        return -1;
    sc->ticks_per_segment = per_segment;
    sc->dir_setup_ticks = (uint32_t)setup;
    sc->min_step_interval = interval;
    return 0;
}

int fw_limits_from_params(const fw_param_set *s, uint32_t step_hz, uint32_t segment_hz,
                          tse_geometry *g, fw_limits *lim)
{
    tse_params kp;
    stepgen_config sc;
    if (fw_params_check(s) >= 0)
        return -1;
    fw_params_kinematics(s, &kp);
    if (fw_stepgen_config_from_params(s, step_hz, segment_hz, &sc) != 0)
        return -1;
    const tse_real micro = TSE_R(1e-6);
    const tse_real spm = (tse_real)s->v[FP_STEPS_PER_M];
    /* The step generator's ceiling, with room for the half-step rounding of each segment; a
     * segment that reverses loses its direction set-up. */
    const tse_real by_rate = FW_STEP_RATE_MARGIN * (tse_real)s->v[FP_STEP_RATE_MAX] / spm;
    const tse_real by_isr = FW_STEP_RATE_MARGIN * (tse_real)stepgen_capacity(&sc, true) *
                            (tse_real)segment_hz / spm;
    tse_real vmax = (tse_real)s->v[FP_SLIDE_VMAX] * micro;
    if (by_rate < vmax)
        vmax = by_rate;
    if (by_isr < vmax)
        vmax = by_isr;
    /* The geometry last: tse_geometry_init leaves it untouched when it refuses, so a refused set
     * changes neither output. */
    if (tse_geometry_init(g, &kp) != TSE_PARAM_OK)
        return -1;
    lim->slide_vmax = vmax;
    lim->slide_amax = (tse_real)s->v[FP_SLIDE_AMAX] * micro;
    lim->plate_vmax = (tse_real)s->v[FP_PLATE_VMAX] * micro;
    lim->plate_amax = (tse_real)s->v[FP_PLATE_AMAX] * micro;
    lim->plate_jmax = (tse_real)s->v[FP_PLATE_JMAX] * micro;
    lim->plate_wmax = (tse_real)s->v[FP_PLATE_WMAX] * micro;
    lim->plate_dwmax = (tse_real)s->v[FP_PLATE_DWMAX] * micro;
    lim->segment_hz = (tse_real)segment_hz;
    return 0;
}
