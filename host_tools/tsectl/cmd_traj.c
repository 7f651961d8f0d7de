/* trajectory FILE: a timed path, checked whole before anything is sent, then streamed with flow
 * control.  The rule a user can rely on: a file either runs to its last row, or (a row refused
 * while streaming, the controller faulting, Ctrl-C) tsectl stops the robot with STOP, waits until
 * it is at rest, and exits non-zero naming the row; it never leaves part of a path running.  A
 * trajectory ended by something tsectl did not do (a STOP from elsewhere, a fault, an underrun, an
 * e-stop) is named as such, from the controller's own report (TRAJ_END, and the refusal of a row
 * that came after it).
 *
 * Streaming keeps the controller's queue ahead: rows go out as ACK and STATUS report free slots,
 * up to PROTO_TRAJ_WINDOW of them in flight, their answers read as they come (in order, as the
 * controller sends them).  A row refused queue_full (a report was behind) is sent again, with the
 * rows after it (refused `order` meanwhile), once there is room. */
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "ctl_info.h"
#include "ctl_params.h"
#include "progress.h"
#include "reject_text.h"
#include "telemetry.h"
#include "traj_check.h"
#include "traj_send.h"

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
    if (link_telemetry(l, true) < 0)
        return -1;
    const uint64_t end = link_now_us() + 1000000u;
    proto_message m;
    int rc = -1;
    while (rc < 0 && link_now_us() < end && !tsectl_interrupted) {
        if (link_recv(l, &m, 50) == 1)
            telemetry_take(t, &m);
        if (telemetry_has_slides(t) && telemetry_has_pose(t))
            rc = 0;
    }
    return link_telemetry(l, false) < 0 ? -1 : rc;
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

typedef struct {
    tlink *l;
    const char *path;
    const traj_row *rows;
    int n;
    uint8_t id;           /* the trajectory's identity: its first row's sequence number */
    int next;             /* the next row to send */
    int taken;            /* rows acknowledged */
    int flight[PROTO_TRAJ_WINDOW]; /* rows sent, not yet answered, oldest first */
    int in_flight;
    int credit;           /* rows the controller has room for beyond those in flight */
    int resend;           /* the row refused queue_full, to send again once those in flight are answered; -1 */
    bool ended;           /* the controller ended the trajectory before its last row */
    int ended_row;        /* the first row refused `ended` (its answer in refusal), or -1 */
    proto_message refusal;
    uint64_t t_first, t_last; /* the first row sent, the last acknowledged */
    int full_rows;        /* rows taken when the queue first filled (the host's own pace until then), or 0 */
    uint64_t t_full;
    uint64_t t_answer;    /* the latest answer, or the oldest row in flight's send */
} streamer;

static uint8_t row_seq(const streamer *s, int i)
{
    return (uint8_t)(s->id + (unsigned)i);
}

static int send_row(streamer *s)
{
    const int i = s->next;
    const int seq = row_seq(s, i);
    const int32_t flags = (i == 0 ? (int32_t)PROTO_TRAJ_FIRST : 0) | (i == s->n - 1 ? (int32_t)PROTO_TRAJ_LAST : 0);
    const int32_t commit[4] = {seq, (int32_t)traj_dt_us(s->rows, i), flags, s->id};
    if (ctl_send_pose(s->l, seq, s->rows[i].p) != 0 || link_send(s->l, PM_TRAJ_COMMIT, commit) != 0) {
        ctl_error("%s:%d: cannot send row %d on the bus", s->path, s->rows[i].line, i + 1);
        return EXIT_BUS;
    }
    if (s->in_flight == 0)
        s->t_answer = link_now_us();
    if (i == 0)
        s->t_first = link_now_us();
    s->flight[s->in_flight++] = i;
    ++s->next;
    --s->credit;
    return EXIT_OK;
}

/* The answer to the oldest row in flight.  Returns EXIT_OK, or EXIT_REJECTED for a refusal that
 * ends streaming (reported). */
static int take_answer(streamer *s, const proto_message *m, progress *p)
{
    const int i = s->flight[0];
    memmove(s->flight, s->flight + 1, (size_t)--s->in_flight * sizeof s->flight[0]);
    s->t_answer = link_now_us();
    if (m->msg == PM_ACK) {
        ++s->taken;
        s->t_last = s->t_answer;
        s->credit = (int)m->v[3] - s->in_flight;
        if (m->v[3] == 0 && s->full_rows == 0) {
            s->full_rows = s->taken;
            s->t_full = s->t_answer;
        }
        char detail[64];
        snprintf(detail, sizeof detail, "(%d of %d rows)", s->taken, s->n);
        progress_update(p, (double)s->taken / s->n, detail);
        return EXIT_OK;
    }
    const int reason = (int)m->v[2];
    if (reason == FW_REASON_QUEUE_FULL && s->resend < 0) {
        s->resend = i; /* a report was behind: the rows after it are refused `order` */
        s->credit = 0;
    } else if (reason == FW_REASON_ORDER && s->resend >= 0) {
        /* expected: behind the row to send again */
    } else if (reason == FW_REASON_ENDED) {
        s->ended = true;
        if (s->ended_row < 0) {
            s->ended_row = i;
            s->refusal = *m;
        }
    } else {
        row_error(s->path, &s->rows[i], i, m, "was refused by the controller");
        return EXIT_REJECTED;
    }
    if (s->resend >= 0 && s->in_flight == 0) {
        s->next = s->resend;
        s->resend = -1;
    }
    return EXIT_OK;
}

static bool is_row_answer(const streamer *s, const proto_message *m)
{
    return (m->msg == PM_ACK || m->msg == PM_REJECT) && m->v[0] == proto_table[PM_TRAJ_COMMIT].function &&
           s->in_flight > 0 && m->v[1] == row_seq(s, s->flight[0]);
}

/* How the trajectory ended, when the controller ended it before its last row (TRAJ_END, or the
 * refusal of a row that came after it).  Says which row, what ended it and, for an underrun, how
 * late the host was and how fast it streamed. */
static void report_end(const streamer *s)
{
    const tlink *l = s->l;
    const bool have_end = l->traj_end_seen && l->traj_end.v[0] == s->id;
    const int how = have_end ? (int)l->traj_end.v[1] : s->ended_row >= 0 ? (int)s->refusal.v[5] & 15 : FW_TRAJ_END_NONE;
    const int fault = have_end ? (int)l->traj_end.v[2] : s->ended_row >= 0 ? (int)s->refusal.v[5] >> 4 : 0;
    /* The first row it did not take. */
    const int row = have_end ? (int)l->traj_end.v[3] : s->ended_row >= 0 ? s->ended_row : s->taken;
    const int k = row < s->n ? row : s->n - 1;
    char what[160];
    if (how == FW_TRAJ_END_STOP)
        snprintf(what, sizeof what, "was stopped by a STOP that tsectl did not send (another terminal or program)");
    else if (how == FW_TRAJ_END_FAULT && fault == FW_FAULT_UNDERRUN)
        snprintf(what, sizeof what, "ran out of path at the controller (underrun): the host fell behind");
    else if (how == FW_TRAJ_END_FAULT && fault == FW_FAULT_ESTOP)
        snprintf(what, sizeof what, "was ended by an e-stop");
    else if (how == FW_TRAJ_END_FAULT)
        snprintf(what, sizeof what, "was ended by a %s fault", proto_enum_name(proto_fault_names, fault));
    else
        snprintf(what, sizeof what, "was ended by the controller");
    if (row < s->n)
        ctl_error("%s:%d: the trajectory %s after %d of %d rows; row %d (t = %.6g s) was not taken", s->path,
                  s->rows[k].line, what, row, s->n, k + 1, s->rows[k].t);
    else
        ctl_error("%s:%d: the trajectory %s before it reached its last row (t = %.6g s); all %d rows had been taken",
                  s->path, s->rows[k].line, what, s->rows[k].t, s->n);
    if (s->ended_row == row)
        row_error(s->path, &s->rows[row], row, &s->refusal, "was refused");
    else if (how == FW_TRAJ_END_FAULT && fault == FW_FAULT_UNDERRUN)
        ctl_error("row %d had not been sent when the controller needed it", k + 1);
    if (how == FW_TRAJ_END_FAULT && fault == FW_FAULT_UNDERRUN && s->taken > 1 && s->t_last > s->t_first)
        ctl_error("streaming reached %.0f rows/s; the file's rows come %.0f per second",
                  (s->taken - 1) / ((double)(s->t_last - s->t_first) * 1e-6), s->n / s->rows[s->n - 1].t);
}

/* After an end tsectl did not cause: the controller is already bringing the robot to rest. */
static int ended_elsewhere(streamer *s)
{
    report_end(s);
    proto_message last;
    if (ctl_wait_rest(s->l, 0, "stopping", 0, &last) == EXIT_INTERRUPTED) {
        stop_at_rest(s->l);
        return EXIT_INTERRUPTED;
    }
    return EXIT_REJECTED;
}

static int stream(tlink *l, const char *path, const traj_row *rows, int n, int seq, int free_slots)
{
    streamer s;
    memset(&s, 0, sizeof s);
    s.l = l;
    s.path = path;
    s.rows = rows;
    s.n = n;
    s.id = (uint8_t)seq;
    s.credit = free_slots;
    s.resend = -1;
    s.ended_row = -1;
    l->traj_end_seen = false;
    progress p;
    progress_start(&p, "streaming", -1);
    while (s.taken < n) {
        if (tsectl_interrupted)
            return ctl_error("interrupted at row %d", s.taken + 1), stop_at_rest(l), EXIT_INTERRUPTED;
        while (!s.ended && s.resend < 0 && s.next < n && s.in_flight < PROTO_TRAJ_WINDOW && s.credit > 0) {
            const int rc = send_row(&s);
            if (rc != EXIT_OK)
                return stop_at_rest(l), rc;
        }
        const bool end_seen = l->traj_end_seen && l->traj_end.v[0] == s.id && l->traj_end.v[1] != FW_TRAJ_END_DONE;
        if ((s.ended || end_seen) && s.in_flight == 0)
            return ended_elsewhere(&s);
        s.ended = s.ended || end_seen;
        proto_message m;
        const int r = link_recv(l, &m, 50);
        if (r < 0) {
            ctl_error("cannot read the bus while streaming row %d", s.taken + 1);
            return stop_at_rest(l), EXIT_BUS;
        }
        if (r == 0) {
            if (s.in_flight > 0 && link_now_us() - s.t_answer > (uint64_t)tsectl_timeout_ms * 1000u) {
                ctl_error("%s:%d: no answer to row %d from node %u within %d ms (--timeout MS waits longer)", path,
                          rows[s.flight[0]].line, s.flight[0] + 1, l->node, tsectl_timeout_ms);
                return stop_at_rest(l), EXIT_TIMEOUT;
            }
            continue;
        }
        if (is_row_answer(&s, &m)) {
            if (take_answer(&s, &m, &p) != EXIT_OK)
                return stop_at_rest(l), EXIT_REJECTED;
        } else if (m.msg == PM_STATUS) {
            /* Rows in flight take slots the report does not know of yet. */
            s.credit = (int)m.v[4] - s.in_flight;
            if ((m.v[0] == FW_STATE_FAULT || m.v[0] == FW_STATE_ESTOP) && s.taken > 0)
                s.ended = true; /* its TRAJ_END says how, if it came */
        }
    }
    progress_break();
    const double sent_s = (double)(s.t_last - s.t_first) * 1e-6, fill_s = (double)(s.t_full - s.t_first) * 1e-6;
    printf("%d rows streamed in %.2f s (%.0f rows/s; the file's rows come %.0f per second)", n, sent_s,
           sent_s > 0 ? (n - 1) / sent_s : 0.0, n / rows[n - 1].t);
    if (s.full_rows > 1 && fill_s > 0)
        printf("; the queue filled after %d rows at %.0f rows/s, then took them at the controller's pace",
               s.full_rows, (s.full_rows - 1) / fill_s);
    printf("\n");
    const int rc = ctl_wait_rest(l, fmax(rows[n - 1].t - sent_s, 0.1), "finishing", 1, NULL);
    if (rc == EXIT_INTERRUPTED) {
        ctl_error("interrupted after the last row was sent");
        stop_at_rest(l);
        return rc;
    }
    if (l->traj_end_seen && l->traj_end.v[0] == s.id && l->traj_end.v[1] != FW_TRAJ_END_DONE) {
        report_end(&s);
        return EXIT_REJECTED;
    }
    return rc;
}

int traj_prepare(tlink *l, bool need_ready, traj_session *s)
{
    memset(s, 0, sizeof *s);
    s->seq = ctl_status_needed(l, &s->st);
    const proto_message *st = &s->st;
    if (s->seq < 0)
        return EXIT_TIMEOUT;
    const int homed = (st->v[2] & PROTO_STATUS_HOMED) != 0;
    if (need_ready && (st->v[0] != FW_STATE_IDLE || !homed)) {
        ctl_error("not started: a trajectory starts at rest from a homed, enabled controller, and node %u is %s%s "
                  "(%s)",
                  l->node, proto_enum_name(proto_state_names, st->v[0]), homed ? "" : " and not homed",
                  st->v[0] == FW_STATE_FAULT || st->v[0] == FW_STATE_ESTOP ? "clear, enable and home first"
                  : st->v[0] == FW_STATE_DISABLED                          ? "enable and home first"
                  : !homed                                                 ? "home first"
                                                                           : "wait for the running motion to end");
        return EXIT_REJECTED;
    }
    int rc = ctl_params_read(l, &s->set);
    if (rc == EXIT_OK)
        rc = ctl_rates(l, &s->rates);
    if (rc != EXIT_OK)
        return rc; /* reported */
    s->have_start = start_point(l, &s->tel) == 0;
    return EXIT_OK;
}

int traj_send(tlink *l, const traj_session *s, const char *path, const traj_row *rows, int n)
{
    traj_check_result chk;
    if (!s->have_start) {
        /* The controller still validates every row, and a refusal still stops the robot. */
        ctl_error("warning: no telemetry from node %u (telemetry_ms is 0?), so the file cannot be checked "
                  "from where the robot is before sending; the controller checks each row as it comes",
                  l->node);
        return stream(l, path, rows, n, s->seq, (int)s->st.v[4]);
    }
    const int c = traj_check(&s->set, s->rates, s->tel.pose, s->tel.slides, rows, n, &chk);
    if (c < 0) {
        ctl_error("node %u's parameters give no valid geometry at its rates (a firmware mismatch?)", l->node);
        return EXIT_REJECTED;
    }
    if (c > 0) {
        row_error(path, &rows[chk.row], chk.row, &chk.why, "would be refused; nothing was sent");
        return EXIT_REJECTED;
    }
    printf("%d rows checked against node %u's limits from where it is: slide speed up to %.0f%% of the "
           "%.4g m/s in effect (%s), acceleration up to %.0f%% of slide_amax\n",
           n, l->node, chk.v_peak * 100.0, chk.v_limit, proto_slide_limits[chk.v_by].name, chk.a_peak * 100.0);
    return stream(l, path, rows, n, s->seq, (int)s->st.v[4]);
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
    traj_session s;
    int rc = traj_prepare(l, true, &s);
    if (rc == EXIT_OK)
        rc = traj_send(l, &s, path, rows, n);
    free(rows);
    return rc;
}
