/* Why the controller refuses a parameter set, in words (param_text.h).  fw_params_judge_config
 * says which rule and which parameter; each rule is worded here with the set's values in SI and
 * the figures that decide it (params.h: each range, then kinematics.md's valid sets through
 * tse_params_check, then the homing switches; limits.h: the STEP pulse and DIR set-up against
 * the step interrupts). */
#include <math.h>
#include <stdio.h>

#include "fw/proto.h"
#include "param_text_internal.h"

typedef struct {
    char t[80];
} words;

/* "NAME = VALUE UNIT" in SI. */
static words said(const fw_param_set *s, int id)
{
    param_key k;
    param_si_key(id, &k);
    char v[64];
    words w;
    snprintf(w.t, sizeof w.t, "%s = %s", fw_param_table[id].name, param_value_words(&k, s->v[id], v, sizeof v));
    return w;
}

static double si(const fw_param_set *s, int id)
{
    param_key k;
    param_si_key(id, &k);
    return s->v[id] / k.per_unit;
}

/* kinematics.md, "Valid parameter sets", for the rules no single range implies. */
static void explain_geometry(const fw_param_set *s, int id, char *err, size_t errlen)
{
    static const char *const rule[TSE_PARAM_COUNT] = {
        [TSE_PARAM_L] = "L > 0",
        [TSE_PARAM_K1] = "0 < k1 <= 1",
        [TSE_PARAM_ETA] = "-pi/2 < eta < pi/2 rad",
        [TSE_PARAM_K3] = "k3 >= 0",
        [TSE_PARAM_K4] = "k4 > 0",
        [TSE_PARAM_ALPHA_MIN] = "0 < alpha_min < pi/2 rad",
        [TSE_PARAM_ALPHA_MAX] = "alpha_min < alpha_max < pi/2 rad",
        [TSE_PARAM_S_MIN] = "s_min >= 0",
        [TSE_PARAM_S_MAX] = "s_min < s_max",
        [TSE_PARAM_MU_MIN] = "0 <= mu_min < 1",
        [TSE_PARAM_NU_MIN] = "0 <= nu_min < 1",
    };
    tse_params kp;
    fw_params_kinematics(s, &kp);
    const tse_param_id bad = tse_params_check(&kp);
    const char *r = bad != TSE_PARAM_OK && rule[bad] ? rule[bad] : "of a valid geometry (docs/kinematics.md)";
    if (id >= 0 && id < FP_COUNT)
        snprintf(err, errlen, "%s breaks the rule %s", said(s, id).t, r);
    else
        snprintf(err, errlen, "the geometry breaks the rule %s", r);
}

/* The stroke, or the six switches together against the alpha_max stop (params.h). */
static void explain_switch(const fw_param_set *s, int id, fw_param_rule rule, char *err, size_t errlen)
{
    if (rule == FW_RULE_SWITCH_STROKE) {
        param_key m;
        param_si_key(FP_S_MIN, &m);
        char lo[32], hi[32];
        snprintf(err, errlen, "%s must be within the stroke s_min..s_max = %s..%s m", said(s, id).t,
                 param_to_text(&m, s->v[FP_S_MIN], lo, sizeof lo), param_to_text(&m, s->v[FP_S_MAX], hi, sizeof hi));
        return;
    }
    /* kinematics.md: w = sqrt(sA^2 + sB^2 + 2 cos(2 eta) sA sB); the alpha_max stop is at
     * w = 2 l0 cos(alpha_max). */
    const int j = (id - FP_HOME_SW_1) / 2, a_id = FP_HOME_SW_1 + 2 * j, b_id = a_id + 1;
    const double a = si(s, a_id), b = si(s, b_id), c = cos(2.0 * si(s, FP_ETA));
    const double w2 = a * a + b * b + 2.0 * c * a * b;
    const double w = sqrt(w2 > 0.0 ? w2 : 0.0);
    const double w_lo = 2.0 * si(s, FP_K1) * si(s, FP_L) * cos(si(s, FP_ALPHA_MAX));
    snprintf(err, errlen,
             "%s: the six homing switches cannot be reached together (slides %d and %d at %s and %s make "
             "scissor %d %.6g m wide, narrower than 2 l0 cos(alpha_max) = %.6g m: its alpha_max stop halts "
             "them before the switches)",
             said(s, id).t, 2 * j + 1, 2 * j + 2, said(s, a_id).t, said(s, b_id).t, j + 1, w, w_lo);
}

/* The STEP pulse and the DIR set-up against the controller's step interrupts (limits.h), with the
 * longest value that would fit. */
static void explain_timing(const fw_param_set *s, fw_param_rule rule, fw_rates rates, char *err, size_t errlen)
{
    const uint64_t hz = rates.step_hz, period_ns = 1000000000u / hz;
    const uint32_t interval = fw_step_interval_ticks(s->v[FP_STEP_RATE_MAX], rates.step_hz);
    const uint64_t gap_ns = (uint64_t)interval * 1000000000u / hz;
    const int64_t pulse = s->v[FP_STEP_PULSE_NS];
    const words rate = said(s, FP_STEP_RATE_MAX);
    switch (rule) {
    case FW_RULE_PULSE_PERIOD:
        snprintf(err, errlen,
                 "%s does not end within one step interrupt period, %llu ns at %llu kHz: it must be shorter "
                 "(at most %llu ns)",
                 said(s, FP_STEP_PULSE_NS).t, (unsigned long long)period_ns, (unsigned long long)(hz / 1000u),
                 (unsigned long long)((1000000000u + hz - 1u) / hz - 1u));
        return;
    case FW_RULE_PULSE_LOW:
        snprintf(err, errlen,
                 "%s leaves %lld ns low before the same slide's next step, which may come %llu ns later (%u step "
                 "interrupt%s at %llu kHz for %s): the low time must be at least as long as the pulse (at most "
                 "%llu ns)",
                 said(s, FP_STEP_PULSE_NS).t, (long long)gap_ns - pulse, (unsigned long long)gap_ns, interval,
                 interval == 1 ? "" : "s", (unsigned long long)(hz / 1000u), rate.t,
                 (unsigned long long)((uint64_t)interval * 1000000000u / (2u * hz)));
        return;
    case FW_RULE_DIR_SETUP_ROOM: {
        const uint32_t per_segment = rates.step_hz / rates.segment_hz;
        const uint32_t setup = fw_dir_setup_ticks((uint32_t)s->v[FP_DIR_SETUP_NS], rates.step_hz);
        char most[96] = "";
        if (per_segment > interval + 1u)
            snprintf(most, sizeof most, " (at most %llu ns)",
                     (unsigned long long)((uint64_t)(per_segment - interval - 1u) * 1000000000u / hz));
        snprintf(err, errlen,
                 "%s takes %u step interrupts (rounded up, plus one) of the %u in a control segment, leaving no "
                 "room for a step (%u interrupt%s apart for %s) in a segment that changes direction%s",
                 said(s, FP_DIR_SETUP_NS).t, setup, per_segment, interval, interval == 1 ? "" : "s", rate.t, most);
        return;
    }
    default:
        snprintf(err, errlen, "the controller's rates (%u Hz step interrupts, %u Hz control segments) cannot run it",
                 rates.step_hz, rates.segment_hz);
        return;
    }
}

void param_explain_fault(const fw_param_set *s, fw_param_fault f, fw_rates rates, char *err, size_t errlen)
{
    /* The parameter the judge blames, when it finds the same rule broken. */
    const fw_param_fault own = fw_params_judge_config(s, rates.step_hz, rates.segment_hz);
    const int id = own.rule == f.rule && own.id >= 0 ? own.id : f.id;
    const int known = id >= 0 && id < FP_COUNT;
    switch (f.rule) {
    case FW_RULE_RANGE:
        if (known) {
            param_key k;
            param_si_key(id, &k);
            char v[64];
            param_range_error(&k, s->v[id], param_to_text(&k, s->v[id], v, sizeof v), err, errlen);
            return;
        }
        break;
    case FW_RULE_GEOMETRY:
        explain_geometry(s, id, err, errlen);
        return;
    case FW_RULE_ALPHA_ORDER:
        snprintf(err, errlen, "%s must be below %s", said(s, FP_ALPHA_MIN).t, said(s, FP_ALPHA_MAX).t);
        return;
    case FW_RULE_STROKE_ORDER:
        snprintf(err, errlen, "%s must be below %s", said(s, FP_S_MIN).t, said(s, FP_S_MAX).t);
        return;
    case FW_RULE_SWITCH_STROKE:
    case FW_RULE_SWITCH_REACH:
        if (id >= FP_HOME_SW_1 && id <= FP_HOME_SW_6) {
            explain_switch(s, id, f.rule, err, errlen);
            return;
        }
        break;
    case FW_RULE_PULSE_PERIOD:
    case FW_RULE_PULSE_LOW:
    case FW_RULE_DIR_SETUP_ROOM:
    case FW_RULE_CONFIG:
        explain_timing(s, f.rule, rates, err, errlen);
        return;
    case FW_RULE_NOT_AT_REST:
        snprintf(err, errlen, "the slides were still moving when the set came: set it again at rest");
        return;
    default:
        break;
    }
    /* The rule's own words, for a case without the values to say more. */
    const char *w = proto_code_words(proto_param_rules, (int32_t)f.rule);
    if (w)
        snprintf(err, errlen, "%s", w);
    else
        snprintf(err, errlen, "the set breaks rule %d, which this tool does not know", (int)f.rule);
}

void param_explain_invalid(const fw_param_set *s, fw_rates rates, char *err, size_t errlen)
{
    const fw_param_fault f = fw_params_judge_config(s, rates.step_hz, rates.segment_hz);
    if (f.rule == FW_RULE_NONE)
        snprintf(err, errlen, "the set is valid");
    else
        param_explain_fault(s, f, rates, err, errlen);
}
