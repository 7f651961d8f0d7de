/* Why the firmware refuses a parameter set, in words (param_text.h).  fw_params_check says which
 * parameter is at fault; the case is found by the same rules in the same order (params.h: each
 * range, then kinematics.md's valid sets through tse_params_check, then the homing switches). */
#include <math.h>
#include <stdio.h>

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
static void explain_kinematics(const fw_param_set *s, tse_param_id bad, int id, char *err, size_t errlen)
{
    if (bad == TSE_PARAM_ALPHA_MAX && s->v[FP_ALPHA_MAX] <= s->v[FP_ALPHA_MIN]) {
        snprintf(err, errlen, "%s must be below %s", said(s, FP_ALPHA_MIN).t, said(s, FP_ALPHA_MAX).t);
        return;
    }
    if (bad == TSE_PARAM_S_MAX && s->v[FP_S_MAX] <= s->v[FP_S_MIN]) {
        snprintf(err, errlen, "%s must be below %s", said(s, FP_S_MIN).t, said(s, FP_S_MAX).t);
        return;
    }
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
    snprintf(err, errlen, "%s breaks the rule %s", said(s, id).t, rule[bad] ? rule[bad] : "of a valid geometry");
}

/* The stroke, or the six switches together against the alpha_max stop (params.h). */
static void explain_switch(const fw_param_set *s, int id, char *err, size_t errlen)
{
    const int k = id - FP_HOME_SW_1;
    if (s->v[id] < s->v[FP_S_MIN] || s->v[id] > s->v[FP_S_MAX]) {
        param_key m;
        param_si_key(FP_S_MIN, &m);
        char lo[32], hi[32];
        snprintf(err, errlen, "%s must be within the stroke s_min..s_max = %s..%s m", said(s, id).t,
                 param_to_text(&m, s->v[FP_S_MIN], lo, sizeof lo), param_to_text(&m, s->v[FP_S_MAX], hi, sizeof hi));
        return;
    }
    /* kinematics.md: w = sqrt(sA^2 + sB^2 + 2 cos(2 eta) sA sB); the alpha_max stop is at
     * w = 2 l0 cos(alpha_max). */
    const int j = k / 2, a_id = FP_HOME_SW_1 + 2 * j, b_id = a_id + 1;
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

void param_explain_invalid(const fw_param_set *s, char *err, size_t errlen)
{
    const int id = fw_params_check(s);
    if (id < 0) {
        snprintf(err, errlen, "the set is valid");
        return;
    }
    if (!fw_param_value_ok((uint16_t)id, s->v[id])) {
        param_key k;
        param_si_key(id, &k);
        char v[64];
        param_range_error(&k, s->v[id], param_to_text(&k, s->v[id], v, sizeof v), err, errlen);
        return;
    }
    tse_params kp;
    fw_params_kinematics(s, &kp);
    const tse_param_id bad = tse_params_check(&kp);
    if (bad != TSE_PARAM_OK) {
        explain_kinematics(s, bad, id, err, errlen);
        return;
    }
    if (id >= FP_HOME_SW_1 && id <= FP_HOME_SW_6) {
        explain_switch(s, id, err, errlen);
        return;
    }
    snprintf(err, errlen, "%s is refused", said(s, id).t); /* a rule this file does not know yet */
}
