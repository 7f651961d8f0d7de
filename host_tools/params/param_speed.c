/* The slide speed limit in effect, in words (param_text.h): the lower of slide_vmax and the step
 * generator's limit that fw_speed_limit_from_params works out, and which one it is. */
#include <stdio.h>

#include "param_text_internal.h"

int param_sets_speed_limit(int id)
{
    return id == FP_SLIDE_VMAX || id == FP_STEPS_PER_M || id == FP_STEP_RATE_MAX || id == FP_DIR_SETUP_NS;
}

const char *param_speed_limit_words(const fw_param_set *s, fw_rates rates, char *buf, size_t cap)
{
    fw_speed_limit v;
    if (fw_speed_limit_from_params(s, rates.step_hz, rates.segment_hz, &v) != 0) {
        snprintf(buf, cap, "slide speed limit in effect: none (the step generator cannot run this set)");
        return buf;
    }
    char vmax[64], spm[64], rate[64], dir[64];
    param_key k;
    param_si_key(FP_SLIDE_VMAX, &k);
    param_value_words(&k, s->v[FP_SLIDE_VMAX], vmax, sizeof vmax);
    if (v.by == FW_LIMIT_SLIDE_VMAX) {
        snprintf(buf, cap, "slide speed limit in effect: %s, slide_vmax (the step generator would allow %.4g m/s)",
                 vmax, (double)v.by_steps);
        return buf;
    }
    param_si_key(FP_STEPS_PER_M, &k);
    param_value_words(&k, s->v[FP_STEPS_PER_M], spm, sizeof spm);
    param_si_key(FP_STEP_RATE_MAX, &k);
    param_value_words(&k, s->v[FP_STEP_RATE_MAX], rate, sizeof rate);
    param_si_key(FP_DIR_SETUP_NS, &k);
    param_value_words(&k, s->v[FP_DIR_SETUP_NS], dir, sizeof dir);
    snprintf(buf, cap,
             "slide speed limit in effect: %.4g m/s, set by the step generator: %.1f x %u steps per %g ms control "
             "segment / steps_per_m = %s, %u being the steps that fit in a segment that changes direction (%u step "
             "interrupts at %u kHz, less %u for the DIR set-up of dir_setup_ns = %s, one step every %u for "
             "step_rate_max = %s); slide_vmax = %s is higher",
             (double)v.vmax, (double)FW_STEP_RATE_MARGIN, v.segment_steps, 1000.0 / rates.segment_hz, spm,
             v.segment_steps, v.sc.ticks_per_segment, rates.step_hz / 1000u, v.sc.dir_setup_ticks, dir,
             v.sc.min_step_interval, rate, vmax);
    return buf;
}
