#include "fw/reject.h"

/* A position along the path, u in 0..1, in per mille: clamped before it is converted (a NaN to
 * 0), for a conversion out of an integer's range is undefined. */
static int32_t per_mille(tse_real u)
{
    if (!(u > TSE_R(0.0)))
        return 0;
    return u >= TSE_R(1.0) ? 1000 : (int32_t)(u * TSE_R(1000.0) + TSE_R(0.5));
}

void fw_reject_values(uint8_t function, uint8_t seq, fw_reason reason, uint8_t field,
                      const fw_plan_result *why, int32_t v[PROTO_MAX_FIELDS])
{
    int32_t where = 0, scissor = 0, status = 0, fld = field;
    if (why && reason == FW_REASON_KINEMATICS) {
        scissor = why->scissor;
        status = why->status;
        where = per_mille(why->where);
    } else if (why && reason == FW_REASON_TIMING) {
        scissor = why->scissor;
        fld = why->slide + FW_REJECT_LIMIT * (int32_t)(why->accel ? FW_LIMIT_SLIDE_AMAX : why->limit);
        const tse_real pm = why->ratio * TSE_R(1000.0) + TSE_R(0.5);
        /* Capped to the field, a NaN included: a value out of range would not encode, and the
         * refusal would go unanswered. */
        where = pm < TSE_R(65535.0) ? (pm > TSE_R(0.0) ? (int32_t)pm : 0) : 65535;
    } else if (why && reason == FW_REASON_TOO_LONG && why->status == TSE_OK) {
        where = FW_MOVE_MAX_S; /* field 0: longer than a move may last */
    } else if (why && reason == FW_REASON_TOO_LONG) {
        fld = 1; /* too long to prove near the limit named */
        scissor = why->scissor;
        status = why->status;
        where = per_mille(why->where);
    }
    v[0] = function & 0x7F;
    v[1] = seq;
    v[2] = reason;
    v[3] = scissor;
    v[4] = status;
    v[5] = fld;
    v[6] = where;
}

void fw_reject_param_values(uint8_t function, fw_reason reason, uint16_t id, fw_param_rule rule,
                            int32_t v[PROTO_MAX_FIELDS])
{
    fw_reject_values(function, 0, reason, (uint8_t)(id > 255 ? 255 : id), NULL, v);
    if (reason == FW_REASON_PARAM_SET)
        v[6] = rule;
}
