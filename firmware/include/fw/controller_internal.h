/* Shared between the controller's source files; not part of its contract. */
#ifndef FW_CONTROLLER_INTERNAL_H
#define FW_CONTROLLER_INTERNAL_H

#include "fw/controller.h"

void fw_send(fw_controller *c, proto_msg msg, const int32_t *values);
void fw_ack(fw_controller *c, uint8_t function, uint8_t seq, uint32_t detail);
/* A REJECT (fw/reject.h).  `field` is what the reason names (a field index, a parameter id);
 * FW_REASON_STATE always carries the controller's state, whatever the caller passes. */
void fw_reject(fw_controller *c, uint8_t function, uint8_t seq, fw_reason reason, uint8_t field,
               const fw_plan_result *why);
/* A REJECT of PARAM_GET or PARAM_SET about parameter id, with the rule a refused set breaks. */
void fw_reject_param(fw_controller *c, uint8_t function, fw_reason reason, uint16_t id, fw_param_rule rule);

void fw_set_state(fw_controller *c, fw_state s);
void fw_drives(fw_controller *c, bool on);
/* A fault: a controlled stop first when anything moves, then latched. */
void fw_fault_raise(fw_controller *c, fw_fault f);
/* A controlled stop of whatever moves (homing included). */
void fw_stop_motion(fw_controller *c);
/* Adopts set s: FW_RULE_NONE, or the rule it breaks at this controller's rates (fw/limits.h), or
 * FW_RULE_NOT_AT_REST; nothing changes then. */
fw_param_rule fw_apply_params(fw_controller *c, const fw_param_set *s);

/* Starts motion from a validated source; the caller has filled c->move or c->traj. */
void fw_start_source(fw_controller *c, fw_source src);

void fw_homing_start(fw_controller *c);
void fw_homing_tick(fw_controller *c);

/* Steps of a slide position [m]. */
int32_t fw_to_steps(const fw_controller *c, tse_real s);

/* Slide k's homing switch position (home_sw_k) in steps: the last whole step at which it is
 * pressed, rounded down (the release edge is the step above). */
int32_t fw_home_switch_steps(const fw_controller *c, int k);

/* Completes a pending fw_estop_isr with fw_estop (nothing if none is pending). */
void fw_estop_complete(fw_controller *c);

/* A streamed trajectory's life (traj_run.c, fw_traj_run). */
/* A TRAJ_COMMIT taken: its first row begins the run (with the host's identity), every row counts. */
void fw_traj_run_took(fw_controller *c, uint8_t seq, bool first, uint8_t id);
/* True while the running trajectory's clock waits for the queue to hold enough; starts it once it
 * does. */
bool fw_traj_run_priming(fw_controller *c);
/* Ends the open trajectory (nothing if none is open): how, the fault for FW_TRAJ_END_FAULT. */
void fw_traj_run_end(fw_controller *c, fw_traj_end how, fw_fault f);
/* The ending of the open trajectory, if any, when motion stops or comes to rest with `pending`
 * (the fault to latch, or none): a fault if one is pending, else `otherwise`. */
void fw_traj_run_end_pending(fw_controller *c, fw_traj_end otherwise);
/* Why a TRAJ_COMMIT may not join a trajectory: FW_REASON_NONE, or ORDER or ENDED with the REJECT's
 * field and where in *field, *where.  `ended_only`: only a row of the trajectory that ended last
 * (checked before the state table, so that it is refused `ended` in any state). */
fw_reason fw_traj_row_refusal(const fw_controller *c, const proto_message *m, bool ended_only, uint8_t *field,
                              int32_t *where);
/* Sends a pending TRAJ_END. */
void fw_traj_run_report(fw_controller *c);

#endif
