/* Frames to the host, from the thread: answers and reports, encoded by the message table. */
#ifndef FW_SEND_H
#define FW_SEND_H

#include <stdint.h>

#include "controller_internal.h"
#include "fw/move.h"

/* A message of the table, its field values in table order. */
void fw_send(fw_controller *c, proto_msg msg, const int32_t *values);

/* An ACK, with the trajectory queue's depth and room as the view has them. */
void fw_ack(fw_controller *c, uint8_t function, uint8_t seq, uint32_t detail);

/* A REJECT (fw/reject.h).  `field` is what the reason names (a field index, a parameter id);
 * FW_REASON_STATE always carries the state the view holds, whatever the caller passes. */
void fw_reject(fw_controller *c, uint8_t function, uint8_t seq, fw_reason reason, uint8_t field,
               const fw_plan_result *why);

/* A REJECT of PARAM_GET or PARAM_SET about parameter id, with the rule a refused set breaks. */
void fw_reject_param(fw_controller *c, uint8_t function, fw_reason reason, uint16_t id, fw_param_rule rule);

/* A REJECT of a trajectory row for its place among the trajectories (order, ended): field and
 * where as fw/reject.h has them. */
void fw_reject_row(fw_controller *c, uint8_t function, uint8_t seq, fw_reason reason, uint8_t field, int32_t where);

#endif
