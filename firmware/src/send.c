#include "send.h"

#include "fw/reject.h"

void fw_send(fw_controller *c, proto_msg msg, const int32_t *values)
{
    hal_can_frame f;
    if (proto_encode_values(msg, c->cfg.node, values, &f) == 0)
        c->hal.can.send(c->hal.can.ctx, &f);
}

void fw_ack(fw_controller *c, uint8_t function, uint8_t seq, uint32_t detail)
{
    const uint32_t depth = c->th.view.traj_depth;
    const int32_t v[5] = {function, seq, (int32_t)depth, (int32_t)(FW_TRAJ_CAPACITY - depth),
                          (int32_t)(detail > INT32_MAX ? INT32_MAX : detail)};
    fw_send(c, PM_ACK, v);
}

void fw_reject(fw_controller *c, uint8_t function, uint8_t seq, fw_reason reason, uint8_t field,
               const fw_plan_result *why)
{
    if (reason == FW_REASON_STATE)
        field = c->th.view.state; /* whichever check refused, the host learns the state it refused in */
    int32_t v[PROTO_MAX_FIELDS];
    fw_reject_values(function, seq, reason, field, why, v);
    fw_send(c, PM_REJECT, v);
}

void fw_reject_param(fw_controller *c, uint8_t function, fw_reason reason, uint16_t id, fw_param_rule rule)
{
    int32_t v[PROTO_MAX_FIELDS];
    fw_reject_param_values(function, reason, id, rule, v);
    fw_send(c, PM_REJECT, v);
}

void fw_reject_row(fw_controller *c, uint8_t function, uint8_t seq, fw_reason reason, uint8_t field, int32_t where)
{
    int32_t v[PROTO_MAX_FIELDS];
    fw_reject_values(function, seq, reason, field, NULL, v);
    v[6] = where;
    fw_send(c, PM_REJECT, v);
}
