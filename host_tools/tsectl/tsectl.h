/* What tsectl's commands share: exit statuses, the link's time limit, interruption, and the
 * exchanges every command is made of (a sequence number from STATUS, an answer, a wait for rest).
 *
 * Exit statuses: 0 acknowledged (and, with --wait, at rest without a fault), 1 the bus cannot be
 * used, 2 a usage error or a bad file (nothing was sent), 3 refused (by the controller, or by the
 * same rules checked before sending), 4 no answer in time, 130 interrupted (motion was stopped). */
#ifndef TSECTL_H
#define TSECTL_H

#include <signal.h>
#include <stdarg.h>

#include "fw/proto.h"
#include "link.h"

enum { EXIT_OK = 0, EXIT_BUS = 1, EXIT_USAGE = 2, EXIT_REJECTED = 3, EXIT_TIMEOUT = 4, EXIT_INTERRUPTED = 130 };

/* Set by SIGINT and SIGTERM (cleared by whoever acts on it); tsectl_signals counts them all. */
extern volatile sig_atomic_t tsectl_interrupted;
extern volatile sig_atomic_t tsectl_signals;
extern int tsectl_timeout_ms;

/* "tsectl: ..." on stderr, after ending a progress bar's line. */
void ctl_error(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

/* Waits for a STATUS (up to the time limit).  Returns the sequence number a new commit must use
 * (last accepted + 1, mod 256) with *status filled, or -1. */
int ctl_status(tlink *l, proto_message *status);
/* ctl_status for a command that cannot go on without one: says so on stderr when there is none. */
int ctl_status_needed(tlink *l, proto_message *status);

/* Waits for the ACK or REJECT of (function, seq); seq < 0 matches any.  Returns EXIT_OK with *ack,
 * EXIT_REJECTED with *reject (nothing printed), EXIT_TIMEOUT (printed), EXIT_INTERRUPTED. */
int ctl_answer(tlink *l, int function, int seq, proto_message *ack, proto_message *reject);

/* Follows STATUS until the controller is at rest (idle, disabled, fault, estop) after having been
 * seen moving, or has stayed idle for 2 s without moving.  expected_s > 0 drives the progress
 * display (0: unknown, homing).  Returns EXIT_OK at rest without a fault, EXIT_REJECTED at rest in
 * fault or e-stop (named), EXIT_TIMEOUT, EXIT_INTERRUPTED.  *last gets the final STATUS if given. */
int ctl_wait_rest(tlink *l, double expected_s, const char *what, int show_progress, proto_message *last);

/* After an interrupt (SIGINT, SIGTERM), or another reason `why` (may be NULL) to end a motion the
 * command started: STOP, then wait until the robot is at rest; an interrupt meanwhile sends ESTOP
 * at once.  Says what it does.  Returns EXIT_OK at rest, EXIT_REJECTED at rest in fault or e-stop (the e-stop of
 * a second interrupt included), or the exchange's failure (the robot may still move: said so).
 * After an interrupt the caller exits EXIT_INTERRUPTED whatever it returns. */
int ctl_halt(tlink *l, const char *why);

/* Sends ESTOP at once (no STATUS first) and waits for its answer.  Returns an exit status. */
int ctl_estop(tlink *l);

/* A question (PARAM_GET, INFO_GET): sends msg with `values`, waits for its ACK, then for the
 * `reply` message whose first field is `key` (any, when key < 0).  Returns EXIT_OK with the reply in
 * *out, EXIT_REJECTED with the REJECT in *out (nothing printed), or EXIT_BUS, EXIT_TIMEOUT (said,
 * naming `what` when the reply does not come), EXIT_INTERRUPTED. */
int ctl_ask(tlink *l, proto_msg msg, const int32_t *values, proto_msg reply, int key, const char *what,
            proto_message *out);

/* Sends a one-field command with the next sequence number and waits for its answer; a REJECT is
 * explained.  Returns an exit status; *reject gets a REJECT if given. */
int ctl_simple(tlink *l, proto_msg msg, proto_message *reject);

/* POSE_A, POSE_B and POSE_C of pose p (m, rad) under sequence number seq.  Returns 0 or -1. */
int ctl_send_pose(tlink *l, int seq, const double p[6]);

/* Prints a REJECT in words (reject_text.h) with the command it answered. */
void ctl_print_reject(const proto_message *reject);

#endif
