#include "hal_posix/plant.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "tse/fk.h"
#include "tse/geometry.h"

#if TSE_REAL_FLOAT
#error "the plant is the world: build it in double"
#endif

#define STRIDE_MS 10

_Static_assert(sizeof(tse_geometry) <= PLANT_GEOMETRY_BYTES, "plant_geometry too small for tse_geometry");
_Static_assert(_Alignof(tse_geometry) <= _Alignof(plant_geometry), "plant_geometry under-aligned");

/* The geometry in the plant's bytes: written once by plant_init (a copy), read only here. */
static const tse_geometry *geom(const tse_plant *p)
{
    return (const tse_geometry *)(const void *)p->geom.bytes;
}

static void breach(tse_plant *p, plant_breach b, int axis, const char *what)
{
    if (!p->breaches)
        snprintf(p->first_breach, sizeof p->first_breach, "%s on slide %d at t = %.6f s", what, axis + 1,
                 (double)p->tick / p->cfg.step_hz);
    p->breaches |= (uint32_t)b;
}

int plant_init(tse_plant *p, const plant_config *cfg, const plant_kinematics *kin, const double start[6])
{
    memset(p, 0, sizeof *p);
    const tse_params kp = {kin->L,         kin->k1,    kin->eta,   kin->k3,     kin->k4,    kin->alpha_min,
                           kin->alpha_max, kin->s_min, kin->s_max, kin->mu_min, kin->nu_min};
    tse_geometry built;
    if (tse_geometry_init(&built, &kp) != TSE_PARAM_OK)
        return -1;
    memcpy(p->geom.bytes, &built, sizeof built);
    const tse_geometry *g = geom(p);
    p->cfg = *cfg;
    for (int k = 0; k < 6; ++k) {
        p->steps[k] = llround(start[k] * cfg->steps_per_m);
        /* s <= home_sw in whole steps; a millionth of a step absorbs the decimal conversions. */
        p->sw_steps[k] = (int64_t)floor(cfg->home_sw[k] * cfg->steps_per_m + 1e-6);
    }
    p->pulse_ns = cfg->pulse_ns;
    p->dir_setup_ns = cfg->dir_setup_ns;
    for (int j = 0; j < 2 * STRIDE_MS; ++j)
        for (int k = 0; k < 6; ++k)
            p->hist[j][k] = p->steps[k];
    p->forward = 0x3F;
    for (int k = 0; k < 6; ++k)
        p->pose[k] = g->home_pose[k];
    return 0;
}

/* Whether `ticks` step interrupts last less than ns nanoseconds. */
static int shorter(const tse_plant *p, uint64_t ticks, uint64_t ns)
{
    return ticks * 1000000000u < ns * p->cfg.step_hz;
}

static void set_dir(void *ctx, uint8_t mask)
{
    tse_plant *p = ctx;
    for (int k = 0; k < 6; ++k) {
        if (!(((mask ^ p->forward) >> k) & 1u))
            continue;
        if (((p->stepped >> k) & 1u) && shorter(p, p->tick - p->last_step[k], p->pulse_ns))
            breach(p, PLANT_DIR_SETUP, k, "direction changed while STEP was high");
        p->dir_change[k] = p->tick;
        p->dir_changed |= (uint8_t)(1u << k);
    }
    p->forward = mask;
}

static void pulse(void *ctx, uint8_t mask)
{
    tse_plant *p = ctx;
    const double spm = p->cfg.steps_per_m;
    for (int k = 0; k < 6; ++k) {
        if (!((mask >> k) & 1u))
            continue;
        ++p->pulses;
        p->last_pulse_tick = p->tick;
        if (!p->first_after_mark && p->tick >= p->mark_tick)
            p->first_after_mark = p->tick ? p->tick : 1;
        if (!p->enabled)
            breach(p, PLANT_STEP_DISABLED, k, "step with the drives disabled");
        if (p->last_step[k] && p->tick - p->last_step[k] < p->cfg.min_interval)
            breach(p, PLANT_PULSE_SPACING, k, "steps closer than the minimum interval");
        if (((p->stepped >> k) & 1u) && shorter(p, p->tick - p->last_step[k], 2u * (uint64_t)p->pulse_ns))
            breach(p, PLANT_PULSE_SPACING, k, "steps closer than the pulse's high and low time");
        if (((p->dir_changed >> k) & 1u) && shorter(p, p->tick - p->dir_change[k], p->dir_setup_ns))
            breach(p, PLANT_DIR_SETUP, k, "step within the direction set-up time");
        p->stepped |= (uint8_t)(1u << k);
        /* Speed from the spacing of two steps, allowing one tick of jitter. */
        if (p->last_step[k]) {
            const double dt = (double)(p->tick - p->last_step[k] + 1u) / p->cfg.step_hz;
            if (1.0 / (spm * dt) > p->cfg.vmax * (1.0 + p->cfg.tolerance))
                breach(p, PLANT_OVERSPEED, k, "slide faster than its limit");
        }
        p->last_step[k] = p->tick;
        const int dir = ((p->forward >> k) & 1u) ? 1 : -1;
        p->steps[k] += dir;
        const double s = (double)p->steps[k] / spm;
        if (s < geom(p)->p.s_min - PLANT_OVERTRAVEL || s > geom(p)->p.s_max + PLANT_OVERTRAVEL)
            breach(p, PLANT_BEYOND_STROKE, k, "slide beyond the mechanical stroke");
    }
}

static void enable(void *ctx, bool on)
{
    ((tse_plant *)ctx)->enabled = on;
}

static void timing(void *ctx, uint32_t pulse_ns, uint32_t dir_setup_ns)
{
    tse_plant *p = ctx;
    p->pulse_ns = pulse_ns;
    p->dir_setup_ns = dir_setup_ns;
    ++p->timing_calls;
}

static uint16_t limits(void *ctx)
{
    const tse_plant *p = ctx;
    uint16_t m = 0;
    for (int k = 0; k < 6; ++k) {
        if (p->steps[k] <= p->sw_steps[k])
            m |= (uint16_t)(1u << k);
        if ((double)p->steps[k] / p->cfg.steps_per_m > geom(p)->p.s_max)
            m |= (uint16_t)(1u << (8 + k));
    }
    return m;
}

static bool estop(void *ctx)
{
    return ((tse_plant *)ctx)->estop_open;
}

hal_stepper plant_stepper(tse_plant *p)
{
    return (hal_stepper){p, set_dir, pulse, enable, timing};
}

hal_inputs plant_inputs(tse_plant *p)
{
    return (hal_inputs){p, limits, estop};
}

void plant_tick(tse_plant *p)
{
    ++p->tick;
    const uint64_t per_ms = p->cfg.step_hz / 1000u;
    if (p->tick % per_ms != 0)
        return;
    /* (s_k - 2 s_{k-10} + s_{k-20}) / (10 ms)^2 at every millisecond; one step of quantisation at
     * each of the three positions is allowed for. */
    const double spm = p->cfg.steps_per_m, span = STRIDE_MS * 1e-3;
    int64_t *old2 = p->hist[p->ms % (2 * STRIDE_MS)];
    const int64_t *old1 = p->hist[(p->ms + STRIDE_MS) % (2 * STRIDE_MS)];
    const double slack = 4.0 / (spm * span * span);
    /* With the drives off (an e-stop cuts them at once, by design) there is no commanded motion to
     * judge, and the measure spans 20 ms after it. */
    if (!p->enabled)
        p->quiet_ms = 2 * STRIDE_MS;
    const int judge = p->quiet_ms == 0;
    if (p->quiet_ms > 0)
        --p->quiet_ms;
    for (int k = 0; k < 6; ++k) {
        const double a = (double)(p->steps[k] - 2 * old1[k] + old2[k]) / (spm * span * span);
        if (judge && fabs(a) > p->cfg.amax * (1.0 + p->cfg.tolerance) + slack)
            breach(p, PLANT_OVERACCEL, k, "slide accelerating beyond its limit");
        old2[k] = p->steps[k];
    }
    ++p->ms;
}

void plant_mark(tse_plant *p)
{
    p->mark_tick = p->tick;
    p->first_after_mark = 0;
}

void plant_slides(const tse_plant *p, double s[6])
{
    for (int k = 0; k < 6; ++k)
        s[k] = (double)p->steps[k] / p->cfg.steps_per_m;
}

bool plant_update_pose(tse_plant *p)
{
    double q[6];
    plant_slides(p, q);
    tse_fk_result f;
    if (tse_fk(geom(p), q, p->pose_valid ? p->pose : geom(p)->home_pose, &f) != TSE_OK) {
        p->pose_valid = false;
        return false;
    }
    /* By element: f.pose is tse_real, double only while this file is built in double. */
    for (int k = 0; k < 6; ++k)
        p->pose[k] = (double)f.pose[k];
    p->pose_valid = true;
    return true;
}
