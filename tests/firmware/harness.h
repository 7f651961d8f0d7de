/* A controller on the fake HAL, driven through its CAN interface the way a host would: the
 * helpers the controller-level tests share.  One controller per test executable (F, C). */
#ifndef TESTS_HARNESS_H
#define TESTS_HARNESS_H

#include <stdbool.h>
#include <stdint.h>

#include "fake_hal.h"
#include "fw/command_table.h"
#include "fw/controller.h"
#include "fw/inspect.h"
#include "fw/runtime.h"
#include "fw/testing.h"

extern fake_hal F;
extern fw_controller *C;
extern uint8_t seq; /* the next sequence number cmd() and move_to() use */

/* A pose near the home pose that every test may move to. */
extern const double NEAR[6];

/* A fresh controller, node 1, 1 kHz segments, 100 kHz steps, slides just above their switches. */
void start(void);

/* The controller started again (a power cycle) on hal, as start() configures it. */
void restart(const fw_hal *hal);

/* The controller's observable state now (fw/inspect.h). */
fw_inspection now(void);

void send(proto_msg m, const int32_t *v);
/* A command whose only field is its sequence number. */
void cmd(proto_msg m);
void heartbeat(void);
/* Runs ms milliseconds with the host alive. */
void run(uint32_t ms);
/* POSE_A, B and C of pose p under sequence number s. */
void stage(uint8_t s, const double p[6]);
void move_to(const double p[6], int32_t ms);
/* A trajectory row: p staged and committed under the next sequence number, dt_us after the
 * previous row.  `first` starts a trajectory whose identity is the row's own number (traj_id);
 * the others carry traj_id. */
extern uint8_t traj_id;
void traj_row(const double p[6], uint32_t dt_us, bool first, bool last);
/* What the controller answered since tx index `from` to `function`: 'a' ack, 'r' reject (its
 * reason in *reason), 0 nothing. */
char answer(unsigned from, uint8_t function, uint8_t *reason);
/* The first REJECT of `function` since tx index `from`, decoded (fails the test if none). */
proto_message reject_of(unsigned from, uint8_t function);
/* The newest STATUS since tx index `from`, decoded (fails the test if none). */
proto_message status_since(unsigned from);
/* PARAM_SET of parameter id to value, taken at once (one poll): what the controller answered
 * ('a', 'r' with its reason and, for a refusal, the field it names; 0 nothing). */
char set_param(uint16_t id, int32_t value, uint8_t *reason, uint8_t *field);
/* Enable and home; ends IDLE and homed. */
void home(void);
/* A fresh controller brought into state s. */
void reach(fw_state s);

#endif
