/* trajectory FILE: a timed path, checked whole before anything is sent, then streamed with flow
 * control.  The rule a user can rely on: a file either runs to its last row, or (a row refused
 * while streaming, the controller faulting, Ctrl-C) tsectl stops the robot with STOP, waits until
 * it is at rest, and exits non-zero naming the row; it never leaves part of a path running. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "ctl_params.h"
#include "progress.h"
#include "reject_text.h"
#include "telemetry.h"
#include "traj_check.h"

int check_trajectory(int argc, char **argv, int *done)
{
    (void)done;
    if (argc != 1)
        return usage_error("trajectory", argc ? "takes one FILE" : "needs a CSV FILE", argc > 1 ? argv[1] : NULL);
    traj_row *rows;
    char err[512];
    if (traj_file_read(argv[0], &rows, err, sizeof err) < 0) {
        ctl_error("%s", err);
        return EXIT_USAGE;
    }
    free(rows);
    return EXIT_OK;
}

/* The slides and pose the controller reports, for the check's starting point. */
static int start_point(tlink *l, telemetry *t)
{
    memset(t, 0, sizeof *t);
    const uint64_t end = link_now_us() + 1000000u;
    proto_message m;
    while (link_now_us() < end && !tsectl_interrupted) {
        if (link_recv(l, &m, 50) == 1)
            telemetry_take(t, &m);
        if (telemetry_has_slides(t) && telemetry_has_pose(t))
            return 0;
    }
    return -1;
}

/* STOP, then wait until at rest; an interrupt meanwhile sends ESTOP (ctl_halt). */
static void stop_at_rest(tlink *l)
{
    ctl_halt(l, NULL);
}

static void row_error(const char *path, const traj_row *r, int i, const proto_message *rej, const char *when)
{
    char text[512];
    ctl_error("%s:%d: row %d (t = %.6g s) %s: %s", path, r->line, i + 1, r->t, when, reject_text(rej, text, sizeof text));
}

static int stream(tlink *l, const char *path, const traj_row *rows, int n, int seq, int free_slots)
{
    progress p;
    progress_start(&p, "streaming", -1);
    const uint64_t t0 = link_now_us();
    for (int i = 0; i < n; ++i) {
        /* Flow control: wait for room, as the controller reports it. */
        while (free_slots <= 0) {
            proto_message m;
            if (tsectl_interrupted)
                return ctl_error("interrupted at row %d", i + 1), stop_at_rest(l), EXIT_INTERRUPTED;
            if (link_recv(l, &m, 100) != 1 || m.msg != PM_STATUS)
                continue;
            free_slots = (int)m.v[4];
            if (m.v[0] != FW_STATE_MOVING && m.v[0] != FW_STATE_IDLE) {
                ctl_error("the controller stopped (%s, fault %s) while row %d waited to be sent",
                          proto_enum_name(proto_state_names, m.v[0]), proto_enum_name(proto_fault_names, m.v[1]), i + 1);
                stop_at_rest(l);
                return EXIT_REJECTED;
            }
        }
        if (tsectl_interrupted)
            return ctl_error("interrupted at row %d", i + 1), stop_at_rest(l), EXIT_INTERRUPTED;
        const int s = (uint8_t)seq;
        const int32_t commit[3] = {s, (int32_t)traj_dt_us(rows, i), i == n - 1};
        if (ctl_send_pose(l, s, rows[i].p) != 0 || link_send(l, PM_TRAJ_COMMIT, commit) != 0) {
            ctl_error("%s:%d: cannot send row %d on the bus", path, rows[i].line, i + 1);
            stop_at_rest(l);
            return EXIT_BUS;
        }
        proto_message ack, rej;
        const int rc = ctl_answer(l, proto_table[PM_TRAJ_COMMIT].function, s, &ack, &rej);
        seq = (uint8_t)(seq + 1);
        if (rc == EXIT_REJECTED && rej.v[2] == FW_REASON_QUEUE_FULL) {
            free_slots = 0; /* the status was behind: wait for room and send the row again */
            --i;
            continue;
        }
        if (rc != EXIT_OK) {
            if (rc == EXIT_REJECTED)
                row_error(path, &rows[i], i, &rej, "was refused by the controller");
            else if (rc == EXIT_INTERRUPTED)
                ctl_error("interrupted at row %d", i + 1);
            stop_at_rest(l);
            return rc;
        }
        free_slots = (int)ack.v[3];
        char detail[64];
        snprintf(detail, sizeof detail, "(%d of %d rows)", i + 1, n);
        progress_update(&p, (double)(i + 1) / n, detail);
    }
    progress_break();
    const double sent_s = (double)(link_now_us() - t0) * 1e-6;
    printf("%d rows streamed in %.2f s\n", n, sent_s);
    const int rc = ctl_wait_rest(l, fmax(rows[n - 1].t - sent_s, 0.1), "finishing", 1, NULL);
    if (rc == EXIT_INTERRUPTED) {
        ctl_error("interrupted after the last row was sent");
        stop_at_rest(l);
    }
    return rc;
}

int run_trajectory(tlink *l, int argc, char **argv)
{
    (void)argc;
    const char *path = argv[0];
    traj_row *rows;
    char err[512];
    const int n = traj_file_read(path, &rows, err, sizeof err);
    if (n < 0) {
        ctl_error("%s", err);
        return EXIT_USAGE;
    }
    int rc = EXIT_OK;
    proto_message st;
    const int seq = ctl_status_needed(l, &st);
    fw_param_set set;
    telemetry tel;
    traj_check_result chk;
    if (seq < 0) {
        rc = EXIT_TIMEOUT;
    } else if (st.v[0] != FW_STATE_IDLE || !(st.v[2] & 1)) {
        ctl_error("not started: a trajectory starts at rest from a homed, enabled controller, and node %u is %s%s "
                  "(%s)",
                  l->node, proto_enum_name(proto_state_names, st.v[0]), st.v[2] & 1 ? "" : " and not homed",
                  st.v[0] == FW_STATE_FAULT || st.v[0] == FW_STATE_ESTOP ? "clear, enable and home first"
                  : st.v[0] == FW_STATE_DISABLED                         ? "enable and home first"
                  : !(st.v[2] & 1)                                       ? "home first"
                                                                         : "wait for the running motion to end");
        rc = EXIT_REJECTED;
    } else if ((rc = ctl_params_read(l, &set)) != EXIT_OK) {
        /* reported */
    } else if (start_point(l, &tel) != 0) {
        /* The controller still validates every row, and a refusal still stops the robot. */
        ctl_error("warning: no telemetry from node %u (telemetry_ms is 0?), so the file cannot be checked "
                  "from where the robot is before sending; the controller checks each row as it comes",
                  l->node);
        rc = stream(l, path, rows, n, seq, (int)st.v[4]);
    } else {
        const int c = traj_check(&set, tel.pose, tel.slides, rows, n, &chk);
        if (c < 0) {
            ctl_error("node %u's parameters give no valid geometry (a firmware mismatch?)", l->node);
            rc = EXIT_REJECTED;
        } else if (c > 0) {
            row_error(path, &rows[chk.row], chk.row, &chk.why, "would be refused; nothing was sent");
            rc = EXIT_REJECTED;
        } else {
            printf("%d rows checked against node %u's limits from where it is: slide speed up to %.0f%%, "
                   "acceleration up to %.0f%% of the limits\n",
                   n, l->node, chk.v_peak * 100.0, chk.a_peak * 100.0);
            rc = stream(l, path, rows, n, seq, (int)st.v[4]);
        }
    }
    free(rows);
    return rc;
}
