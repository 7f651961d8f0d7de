#include "plant_check.h"

#include <string.h>

#include "fuzz_target.h"

#define NEVER UINT64_MAX

static struct {
    fw_param_set p;
    uint64_t last_pulse[6]; /* tick of each slide's last step (NEVER: none since the reset) */
    uint64_t last_dir[6];   /* tick of each slide's last direction change */
    int32_t window_start[6];
    bool window_open;
    uint8_t zero_suspect;
} pc;

void plant_check_zero_suspect(uint8_t mask)
{
    pc.zero_suspect = mask;
}

void plant_check_reset(const rig *r, const fw_param_set *params)
{
    (void)r;
    pc.p = *params;
    for (int k = 0; k < 6; ++k)
        pc.last_pulse[k] = pc.last_dir[k] = NEVER;
    pc.window_open = false;
}

void plant_check_dir(const rig *r, uint8_t forward_mask)
{
    const uint8_t changed = (uint8_t)(forward_mask ^ r->f.forward_mask);
    for (int k = 0; k < 6; ++k)
        if ((changed >> k) & 1u)
            pc.last_dir[k] = r->tick;
}

void plant_check_pulse(const rig *r, uint8_t mask, bool estop_cut)
{
    const fw_state s = fw_state_of(r->c);
    /* docs/controller.md ("States", "E-stop"): stepping only moves a robot that is homing, moving
     * or stopping, through energised drives; an e-stop cuts it at once, from the interrupt on. */
    FUZZ_CHECK((mask & ~0x3Fu) == 0);
    FUZZ_CHECK(r->f.enabled);
    FUZZ_CHECK(s == FW_STATE_HOMING || s == FW_STATE_MOVING || s == FW_STATE_STOPPING);
    FUZZ_CHECK(!estop_cut);
    const uint64_t step_hz = r->cfg.step_hz;
    const uint64_t rate = (uint64_t)pc.p.v[FP_STEP_RATE_MAX];
    /* dir_setup_ns rounded up to whole step interrupts, at least one (docs/protocol.md). */
    uint64_t setup = ((uint64_t)pc.p.v[FP_DIR_SETUP_NS] * step_hz + 999999999u) / 1000000000u;
    if (setup < 1)
        setup = 1;
    for (int k = 0; k < 6; ++k) {
        if (!((mask >> k) & 1u))
            continue;
        /* step_rate_max: two steps of one slide at least 1 / step_rate_max apart. */
        if (pc.last_pulse[k] != NEVER)
            FUZZ_CHECK((r->tick - pc.last_pulse[k]) * rate >= step_hz);
        if (pc.last_dir[k] != NEVER)
            FUZZ_CHECK(r->tick - pc.last_dir[k] >= setup);
        pc.last_pulse[k] = r->tick;
    }
}

void plant_check_stroke(const rig *r)
{
    /* Once homed the controller knows where the slides are, and none may leave [s_min, s_max]
     * (docs/controller.md, "What motion keeps to"), read on the plant's true step count with the
     * parameters in force, give or take the one step of rounding a setpoint to whole steps.
     * Before the zero nothing can be promised of the stroke: homing moves the slides blind, down
     * to their switches (a slide brakes past its switch, and a switch may sit at s_min), and a
     * slide that starts on its switch goes up homing_backoff past the release first, which may
     * carry it beyond s_max when a switch sits within homing_backoff of it (a set the controller
     * accepts).  What homing must respect is checked on every tick all the same: the speed and
     * the step rules below, and the stroke from the moment the controller says it is homed (the
     * move to the home pose has ended by then, so the home pose's slides are checked too). */
    if (!fw_homed_of(r->c))
        return;
    const int64_t spm = pc.p.v[FP_STEPS_PER_M];
    for (int k = 0; k < 6; ++k) {
        if ((pc.zero_suspect >> k) & 1u)
            continue;
        const int64_t um_x_spm = (int64_t)r->f.steps[k] * 1000000; /* position [um] x spm */
        FUZZ_CHECK(um_x_spm >= (int64_t)pc.p.v[FP_S_MIN] * spm - 1000000);
        FUZZ_CHECK(um_x_spm <= (int64_t)pc.p.v[FP_S_MAX] * spm + 1000000);
    }
}

void plant_check_segment(const rig *r)
{
    /* The slide speed limit (docs/controller.md, "What the simulator's plant checks": no slide
     * above it), measured as the steps over one segment period: slide_vmax in steps per segment,
     * plus the rounding of the setpoints to whole steps and a window that straddles two segments
     * (two steps), plus one. */
    const double per_segment = (double)pc.p.v[FP_SLIDE_VMAX] * 1e-6 * (double)pc.p.v[FP_STEPS_PER_M] /
                               (double)r->cfg.segment_hz;
    const int64_t bound = (int64_t)per_segment + 3;
    if (pc.window_open) {
        for (int k = 0; k < 6; ++k) {
            int64_t d = (int64_t)r->f.steps[k] - pc.window_start[k];
            if (d < 0)
                d = -d;
            FUZZ_CHECK(d <= bound);
        }
    }
    memcpy(pc.window_start, r->f.steps, sizeof pc.window_start);
    pc.window_open = true;
    plant_check_stroke(r);
}
