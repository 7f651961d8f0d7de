/* The REJECT frame's values for a refusal: one encoding, shared by the controller (fw_reject) and
 * by host tools that predict what it would answer (tsectl checking a trajectory offline).
 *
 * Beyond function, seq and reason, the fields name:
 * - scissor: KINEMATICS, the first failing scissor 1..3; TIMING, the scissor of the slide over
 *   its limit; TOO_LONG near a limit, the scissor the proof stopped at; otherwise 0.  kin_status:
 *   KINEMATICS and TOO_LONG near a limit only, otherwise 0.
 * - field: RANGE, the offending field's index; PARAM_UNKNOWN, PARAM_RANGE, PARAM_SET, the
 *   parameter id (255 for one above); STATE, the fw_state that refused; TIMING, the slide 1..6
 *   (A1, B1, A2, B2, A3, B3: q index + 1) with the worst demand, plus FW_REJECT_LIMIT times the
 *   limit it is against (fw_slide_limit: 0 slide_vmax, 1 slide_amax, which makes the old
 *   "+16: acceleration", 2 the step generator's speed limit); TOO_LONG, 0 in time, 1 near a
 *   limit; otherwise 0.
 * - where: KINEMATICS, the failing point's position along the path in per mille (0..1000);
 *   TIMING, the demand in per mille of the limit field names (1000: at it; 1350: 35 % over), at
 *   most 65535; PARAM_SET, the rule the set breaks (fw_param_rule); TOO_LONG, with field 0 (a move
 *   longer than a move may last) FW_MOVE_MAX_S in s, with field 1 (a move too long to prove near a
 *   limit, which scissor and kin_status name) the position along the path in per mille. */
#ifndef FW_REJECT_H
#define FW_REJECT_H

#include <stdint.h>

#include "fw/move.h"
#include "fw/params.h"
#include "fw/proto_wire.h"
#include "fw/types.h"

/* A timing refusal's field: slide + FW_REJECT_LIMIT * limit (the message table's stride). */
#define FW_REJECT_LIMIT PROTO_REJECT_LIMIT_STRIDE
#define FW_REJECT_ACCEL (FW_REJECT_LIMIT * FW_LIMIT_SLIDE_AMAX)

/* v[] in REJECT's field order (function, seq, reason, scissor, kin_status, field, where), every
 * value inside its field's range.  `field` is what the reason names (for STATE the state, the
 * caller's to give); why (may be NULL) supplies KINEMATICS' and TIMING's details, and for TIMING
 * the field. */
void fw_reject_values(uint8_t function, uint8_t seq, fw_reason reason, uint8_t field,
                      const fw_plan_result *why, int32_t v[PROTO_MAX_FIELDS]);

/* The same for a refusal about parameter id (PARAM_UNKNOWN, PARAM_RANGE, PARAM_SET), and for
 * PARAM_SET the rule the set breaks. */
void fw_reject_param_values(uint8_t function, fw_reason reason, uint16_t id, fw_param_rule rule,
                            int32_t v[PROTO_MAX_FIELDS]);

#endif
