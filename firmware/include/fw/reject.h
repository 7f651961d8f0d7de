/* The REJECT frame's values for a refusal: one encoding, shared by the controller (fw_reject) and
 * by host tools that predict what it would answer (tsectl checking a trajectory offline).
 *
 * Beyond function, seq and reason, the fields name:
 * - scissor: KINEMATICS, the first failing scissor 1..3; TIMING, the scissor of the slide over
 *   its limit; otherwise 0.  kin_status: KINEMATICS only, otherwise 0.
 * - field: RANGE, the offending field's index; PARAM_UNKNOWN, PARAM_RANGE, PARAM_SET, the
 *   parameter id; STATE, the fw_state that refused; TIMING, the slide 1..6 (A1, B1, A2, B2, A3,
 *   B3: q index + 1) with the worst demand, plus FW_REJECT_ACCEL when that demand is an
 *   acceleration rather than a speed; otherwise 0.
 * - where: KINEMATICS, the failing point's position along the path in per mille (0..1000);
 *   TIMING, the demand in per mille of the limit parameter (1000: at it; 1350: 35 % over), at
 *   most 65535. */
#ifndef FW_REJECT_H
#define FW_REJECT_H

#include <stdint.h>

#include "fw/move.h"
#include "fw/proto_table.h"
#include "fw/types.h"

#define FW_REJECT_ACCEL 16

/* v[] in REJECT's field order (function, seq, reason, scissor, kin_status, field, where), every
 * value inside its field's range.  `field` is what the reason names (for STATE the state, the
 * caller's to give); why (may be NULL) supplies KINEMATICS' and TIMING's details, and for TIMING
 * the field. */
void fw_reject_values(uint8_t function, uint8_t seq, fw_reason reason, uint8_t field,
                      const fw_plan_result *why, int32_t v[PROTO_MAX_FIELDS]);

#endif
