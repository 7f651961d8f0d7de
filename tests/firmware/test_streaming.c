/* A streamed trajectory's life.  Its clock starts once the controller holds traj_lead of it (or
 * its last row, or a full queue), the plate at rest until then.  Rows join it in sequence: after
 * a row refused for a full queue the next is refused `order`, and both are taken when sent again.
 * Once a stop, a fault, an underrun or an e-stop ends it, no row is taken for it any more (a row
 * of it is refused `ended`, saying how and how long before it came, and never starts another
 * trajectory), TRAJ_END says once how it ended, and at rest its queue is empty (depth 0, the whole
 * capacity free, in STATUS and in acknowledgements); a new trajectory then starts from the rest
 * pose with a first row. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "harness.h"

#define TRAJ_FN 0x0E

/* Stages p and commits it as a row of the running trajectory, dt_us after the previous one. */
static void point(const double p[6], uint32_t dt_us, bool last)
{
    traj_row(p, dt_us, false, last);
}

static unsigned acks_since(unsigned from, uint8_t function)
{
    unsigned n = 0;
    for (unsigned i = from; i < F.tx_count; ++i)
        if ((F.tx[i].id >> 4) == proto_table[PM_ACK].function && F.tx[i].data[0] == function)
            ++n;
    return n;
}

/* From IDLE and homed: n points 50 ms apart rising 1 mm each (the slides at a few mm/s), none
 * flagged last; all accepted, and 300 ms later the robot under way with many still queued. */
static void stream_and_go(unsigned n)
{
    double p[6];
    memcpy(p, now().pose, sizeof p);
    const unsigned from = F.tx_count;
    for (unsigned i = 0; i < n; ++i) {
        p[2] += 0.001;
        traj_row(p, 50000, i == 0, false);
    }
    fw_poll(C);
    assert_int_equal(acks_since(from, TRAJ_FN), n);
    run(300);
    assert_int_equal(fw_state_of(C), FW_STATE_MOVING);
    assert_true(now().traj_depth > n / 3);
}

/* STATUS a while after the controller came to rest: the queue is empty. */
static void assert_status_queue_empty(fw_state want)
{
    const unsigned from = F.tx_count;
    run(200);
    const proto_message st = status_since(from);
    assert_int_equal(st.v[0], want);
    assert_int_equal(st.v[3], 0);
    assert_int_equal(st.v[4], FW_TRAJ_CAPACITY);
}

/* The trajectory runs to its end: at rest within 2 s, no fault, exactly at its last row p. */
static void ends_at(const double p[6])
{
    for (int i = 0; i < 200 && fw_state_of(C) != FW_STATE_IDLE; ++i)
        run(10);
    assert_int_equal(fw_state_of(C), FW_STATE_IDLE);
    assert_int_equal(fw_fault_of(C), FW_FAULT_NONE);
    for (int k = 0; k < 6; ++k)
        assert_true(fabs(now().pose[k] - p[k]) < 1e-9);
}

/* The row sent since tx index `from` refused `ended`, by the STOP that ended its trajectory; the
 * robot then comes to rest, idle, no fault. */
static void refused_ended_by_the_stop(unsigned from)
{
    const proto_message r = reject_of(from, TRAJ_FN);
    assert_int_equal(r.v[2], FW_REASON_ENDED);
    assert_int_equal(r.v[5], FW_TRAJ_END_STOP);
    for (int i = 0; i < 100 && fw_state_of(C) == FW_STATE_STOPPING; ++i)
        run(10);
    assert_int_equal(fw_state_of(C), FW_STATE_IDLE);
    assert_int_equal(fw_fault_of(C), FW_FAULT_NONE);
}

static void test_stop_drops_queue(void **state)
{
    (void)state;
    reach(FW_STATE_IDLE);
    stream_and_go(30);
    cmd(PM_STOP);
    run(10);
    assert_int_equal(fw_state_of(C), FW_STATE_STOPPING);
    /* Nothing more is taken for the stopping trajectory, and the refusal says why. */
    unsigned from = F.tx_count;
    double more[6];
    memcpy(more, now().traj_tail, sizeof more);
    more[2] += 0.001;
    point(more, 50000, false);
    fw_poll(C);
    refused_ended_by_the_stop(from);
    assert_int_equal(now().traj_depth, 0);
    assert_status_queue_empty(FW_STATE_IDLE);

    /* A new trajectory runs from where the robot stopped, on a clock from zero: ten points
     * 0.5 mm down each, the last flagged, ending on the last point to the step. */
    double p[6], rest[6];
    memcpy(rest, now().pose, sizeof rest);
    memcpy(p, rest, sizeof p);
    from = F.tx_count;
    for (int i = 1; i <= 10; ++i) {
        p[2] = (double)lround((rest[2] - 0.0005 * i) * 1e6) * 1e-6; /* as the wire carries it */
        traj_row(p, 50000, i == 1, i == 10);
    }
    fw_poll(C);
    assert_int_equal(acks_since(from, TRAJ_FN), 10);
    assert_int_equal(now().traj_end_us, 500000);
    ends_at(p);
    tse_ik_result ik;
    assert_int_equal(tse_ik(fw_geometry_of(C), p, NULL, &ik), TSE_OK);
    for (int k = 0; k < 6; ++k)
        assert_int_equal(F.steps[k], lround(ik.q[k] * 1280000.0));
    assert_status_queue_empty(FW_STATE_IDLE);
}

/* Another client's STOP arriving while a row is validated: the STOP ends the validation and is
 * answered first; the row is refused as a row of the trajectory the STOP ended, not for the state
 * (stopping) the STOP left, so the host knows its trajectory ended (tse.can's Ended; the VM's
 * tests_sim saw `state`). */
static void test_stop_during_a_rows_validation_refuses_it_ended(void **state)
{
    (void)state;
    reach(FW_STATE_IDLE);
    stream_and_go(30);
    const unsigned from = F.tx_count;
    double more[6];
    memcpy(more, now().traj_tail, sizeof more);
    more[2] += 0.001;
    point(more, 50000, false); /* 50 control segments to validate: the STOP is seen meanwhile */
    cmd(PM_STOP);
    fw_poll(C);
    assert_int_equal(answer(from, proto_table[PM_STOP].function, NULL), 'a');
    refused_ended_by_the_stop(from);
}

/* The host falls silent while streaming: a controlled stop, the fault latched, the queue gone. */
static void test_fault_drops_queue(void **state)
{
    (void)state;
    reach(FW_STATE_IDLE);
    stream_and_go(30);
    for (int i = 0; i < 100 && fw_state_of(C) != FW_STATE_FAULT; ++i)
        fake_run(&F, C, 10); /* no heartbeat */
    assert_int_equal(fw_state_of(C), FW_STATE_FAULT);
    assert_int_equal(fw_fault_of(C), FW_FAULT_WATCHDOG);
    assert_int_equal(now().traj_depth, 0);
    assert_int_equal(now().traj_free, FW_TRAJ_CAPACITY);
    assert_status_queue_empty(FW_STATE_FAULT);
}

/* A STOP at rest ends whatever trajectory is still held: here one left in the queue behind the
 * controller's back, as the fault latch used to. */
static void test_stop_in_fault_drops_queue(void **state)
{
    (void)state;
    reach(FW_STATE_FAULT);
    fw_traj_point pt;
    memset(&pt, 0, sizeof pt);
    memcpy(pt.pose, fw_geometry_of(C)->home_pose, sizeof pt.pose);
    pt.pose[2] += 1e-5;
    pt.q0[0] = 1.0;
    pt.t_us = 50000;
    fw_testing_hold_point(C, &pt);
    assert_int_equal(now().traj_depth, 1);
    const unsigned from = F.tx_count;
    cmd(PM_STOP);
    fw_poll(C);
    const hal_can_frame *ack = fake_last(&F, proto_table[PM_ACK].function, from);
    assert_non_null(ack);
    assert_int_equal(ack->data[0], proto_table[PM_STOP].function);
    assert_int_equal(ack->data[2], 0);
    assert_int_equal(ack->data[3], FW_TRAJ_CAPACITY);
    assert_status_queue_empty(FW_STATE_FAULT);
}

/* An e-stop drops the queue at once: its own acknowledgement already says so. */
static void test_estop_drops_queue(void **state)
{
    (void)state;
    reach(FW_STATE_IDLE);
    stream_and_go(30);
    const unsigned from = F.tx_count;
    cmd(PM_ESTOP);
    fw_poll(C);
    assert_int_equal(fw_state_of(C), FW_STATE_ESTOP);
    const hal_can_frame *ack = fake_last(&F, proto_table[PM_ACK].function, from);
    assert_non_null(ack);
    assert_int_equal(ack->data[0], proto_table[PM_ESTOP].function);
    assert_int_equal(ack->data[2], 0);
    assert_int_equal(ack->data[3], FW_TRAJ_CAPACITY);
    assert_status_queue_empty(FW_STATE_ESTOP);
}

/* The host stops sending before the last point: the underrun stop along what is queued, then the
 * fault, and nothing of the trajectory left. */
static void test_underrun_drops_queue(void **state)
{
    (void)state;
    reach(FW_STATE_IDLE);
    stream_and_go(12);
    for (int i = 0; i < 200 && fw_state_of(C) != FW_STATE_FAULT; ++i)
        run(10);
    assert_int_equal(fw_state_of(C), FW_STATE_FAULT);
    assert_int_equal(fw_fault_of(C), FW_FAULT_UNDERRUN);
    assert_status_queue_empty(FW_STATE_FAULT);
}

/* The control tick alone (the thread preempted), a period at a time, until the underrun's fault. */
static void ticks_until_fault(void *arg, fake_hook_point at)
{
    (void)arg;
    if (at != FAKE_AT_RECEIVE || F.rx_count > 0)
        return; /* the row's frames are still being read */
    F.hook = NULL;
    for (int ms = 0; ms < 2000 && fw_state_of(C) != FW_STATE_FAULT; ++ms)
        fake_tick_alone(&F, C);
}

/* A row the thread has read and is validating when the tick's underrun ends the trajectory: at the
 * hand-over the tick refuses it `ended`, saying how, as every later row of it (it was `state`: the
 * fault the underrun left, which the state table refuses rows in). */
static void test_row_in_the_hand_over_when_the_tick_ends_it_is_refused_ended(void **state)
{
    (void)state;
    reach(FW_STATE_IDLE);
    stream_and_go(12);
    assert_int_equal(fw_state_of(C), FW_STATE_MOVING);
    const unsigned from = F.tx_count;
    double more[6];
    memcpy(more, now().traj_tail, sizeof more);
    more[2] += 0.001;
    point(more, 50000, false);
    /* Once its frames are read, while it is validated, the tick runs until the queue has run out. */
    F.hook = ticks_until_fault;
    fw_poll(C);
    assert_null(F.hook);
    assert_int_equal(fw_fault_of(C), FW_FAULT_UNDERRUN);
    const proto_message r = reject_of(from, TRAJ_FN);
    assert_int_equal(r.v[2], FW_REASON_ENDED);
    assert_int_equal(r.v[5], FW_TRAJ_END_FAULT + 16 * FW_FAULT_UNDERRUN);
    assert_status_queue_empty(FW_STATE_FAULT);
}

/* One millisecond with the host alive (a heartbeat every 10). */
static void one_ms(void)
{
    if ((F.now_us / 1000u) % 10u == 0)
        heartbeat();
    fake_run(&F, C, 1);
}

/* The TRAJ_END the controller sent since tx index `from`; false if none. */
static bool traj_end_since(unsigned from, proto_message *m)
{
    const hal_can_frame *f = fake_last(&F, proto_table[PM_TRAJ_END].function, from);
    if (!f)
        return false;
    assert_int_equal(proto_decode(f, PROTO_TO_HOST, m).reason, FW_REASON_NONE);
    return true;
}

/* The TRAJ_END since tx index `from` says the running trajectory (traj_id) ended `how` (with
 * `fault`) after taking `rows` rows. */
static void assert_traj_end(unsigned from, fw_traj_end how, fw_fault fault, int rows)
{
    proto_message end;
    assert_true(traj_end_since(from, &end));
    assert_int_equal(end.v[0], traj_id);
    assert_int_equal(end.v[1], how);
    assert_int_equal(end.v[2], fault);
    assert_int_equal(end.v[3], rows);
}

/* From IDLE: a trajectory under way (stream_and_go, n rows), then the command m.  Returns the tx
 * index from before the rows; *tail: its newest row's pose. */
static unsigned streaming_then(unsigned n, proto_msg m, double tail[6])
{
    reach(FW_STATE_IDLE);
    const unsigned from = F.tx_count;
    stream_and_go(n);
    memcpy(tail, now().traj_tail, 6 * sizeof tail[0]);
    cmd(m);
    fw_poll(C);
    return from;
}

/* The next row of the trajectory (1 mm above *p, which it updates), sent now: its REJECT, which
 * must say `ended`. */
static proto_message row_after_end(double p[6])
{
    const unsigned from = F.tx_count;
    p[2] += 0.001;
    point(p, 50000, false);
    fw_poll(C);
    const proto_message r = reject_of(from, TRAJ_FN);
    assert_int_equal(r.v[2], FW_REASON_ENDED);
    return r;
}

static unsigned answers_since(unsigned from, uint8_t function)
{
    unsigned n = 0;
    for (unsigned i = from; i < F.tx_count; ++i) {
        const uint8_t fn = (uint8_t)(F.tx[i].id >> 4);
        if ((fn == proto_table[PM_ACK].function || fn == proto_table[PM_REJECT].function) && F.tx[i].data[0] == function)
            ++n;
    }
    return n;
}

/* From IDLE and homed: the rest pose in p; returns its Z. */
static double idle_at(double p[6])
{
    reach(FW_STATE_IDLE);
    memcpy(p, now().pose, 6 * sizeof p[0]);
    return p[2];
}

/* The i-th of n rows of a 2 mm rise in Z with minimum-jerk easing from the pose z0 (as the wire
 * carries it): the README's layout, the first row at the current pose, rows 20 ms apart. */
static void rise_row(double p[6], double z0, int i, int n)
{
    const double s = (double)i / n, e = s * s * s * (10 - 15 * s + 6 * s * s);
    p[2] = (double)lround((z0 + 0.002 * e) * 1e6) * 1e-6;
}

/* The failure: the first row alone, the second 28 ms later (a host that answers slower
 * than real time at first).  The clock waits for traj_lead (0.2 s, ten rows) before the first
 * row's time counts, so there is no underrun, and the trajectory takes its 0.8 s from when the
 * clock started, not from the first row. */
static void test_first_rows_wait_for_the_lead(void **state)
{
    (void)state;
    double p[6];
    const double z0 = idle_at(p);
    const int n = 40;
    const unsigned from = F.tx_count;
    rise_row(p, z0, 0, n);
    traj_row(p, 20000, true, false);
    run(30);
    for (int i = 1; i < 9; ++i) { /* 180 ms held: still short of the lead */
        rise_row(p, z0, i, n);
        traj_row(p, 20000, false, false);
        run(30);
    }
    assert_int_equal(fw_state_of(C), FW_STATE_MOVING);
    assert_int_equal(fw_fault_of(C), FW_FAULT_NONE);
    assert_int_equal(now().segments_run, 0); /* not one setpoint yet: the plate is at rest */
    rise_row(p, z0, 9, n);
    traj_row(p, 20000, false, false); /* 200 ms: the clock starts */
    fw_poll(C);
    const uint64_t t0 = F.now_us;
    for (int i = 10; i < n; ++i) {
        rise_row(p, z0, i, n);
        traj_row(p, 20000, false, i == n - 1);
        run(10);
    }
    assert_true(now().segments_run > 0);
    while (fw_state_of(C) == FW_STATE_MOVING && F.now_us - t0 < 2000000u)
        one_ms();
    assert_int_equal(fw_state_of(C), FW_STATE_IDLE);
    assert_int_equal(fw_fault_of(C), FW_FAULT_NONE);
    fw_poll(C); /* the report goes out with the next poll */
    /* n rows of 20 ms from the clock's start, to within the 2 setpoints queued ahead. */
    const double took_ms = (double)(F.now_us - t0) * 1e-3;
    if (fabs(took_ms - 20.0 * n) > 4.0)
        fail_msg("the trajectory took %.1f ms from the clock's start, not %d", took_ms, 20 * n);
    for (int k = 0; k < 6; ++k)
        assert_true(fabs(now().pose[k] - p[k]) < 1e-9);
    assert_traj_end(from, FW_TRAJ_END_DONE, FW_FAULT_NONE, n);
}

/* A trajectory shorter than the lead runs once its last row is in; one whose rows fill the queue
 * before the lead (traj_lead 10 s here) runs once the queue is full. */
static void test_last_row_or_full_queue_starts_the_clock(void **state)
{
    (void)state;
    double p[6];
    double z0 = idle_at(p);
    for (int i = 1; i <= 3; ++i) {
        rise_row(p, z0, i, 40);
        traj_row(p, 20000, i == 1, i == 3);
    }
    run(100);
    assert_int_equal(fw_state_of(C), FW_STATE_IDLE);
    assert_int_equal(fw_fault_of(C), FW_FAULT_NONE);
    for (int k = 0; k < 6; ++k)
        assert_true(fabs(now().pose[k] - p[k]) < 1e-9);

    start();
    const int32_t lead[2] = {FP_TRAJ_LEAD, 10000000};
    unsigned from = F.tx_count;
    send(PM_PARAM_SET, lead);
    fw_poll(C);
    assert_int_equal(answer(from, proto_table[PM_PARAM_SET].function, NULL), 'a');
    home();
    memcpy(p, now().pose, sizeof p);
    z0 = p[2];
    for (int i = 0; i < (int)FW_TRAJ_CAPACITY - 1; ++i) {
        rise_row(p, z0, i, 200);
        traj_row(p, 20000, i == 0, false);
    }
    run(50);
    assert_int_equal(now().segments_run, 0);
    rise_row(p, z0, FW_TRAJ_CAPACITY - 1, 200);
    traj_row(p, 20000, false, false); /* the queue is full */
    run(50);
    assert_true(now().segments_run >= 45);
    assert_int_equal(fw_state_of(C), FW_STATE_MOVING);
}

/* Rows in flight past a full queue: the first is refused queue_full, the next `order` (naming the
 * number the controller expects); sent again once there is room, both are taken, and the
 * trajectory is the file's, to its last row. */
static void test_rows_after_a_full_queue_wait_their_turn(void **state)
{
    (void)state;
    double p[6];
    const double z0 = idle_at(p);
    const int n = FW_TRAJ_CAPACITY + 2;
    uint8_t seqs[FW_TRAJ_CAPACITY + 2];
    unsigned from = F.tx_count;
    for (int i = 0; i < n; ++i) {
        rise_row(p, z0, i, n);
        seqs[i] = seq;
        traj_row(p, 20000, i == 0, i == n - 1);
    }
    fw_poll(C);
    assert_int_equal(acks_since(from, TRAJ_FN), FW_TRAJ_CAPACITY);
    assert_int_equal(answers_since(from, TRAJ_FN), n);
    unsigned refusals = 0;
    for (unsigned i = from; i < F.tx_count; ++i) {
        if ((F.tx[i].id >> 4) != proto_table[PM_REJECT].function || F.tx[i].data[0] != TRAJ_FN)
            continue;
        proto_message r;
        assert_int_equal(proto_decode(&F.tx[i], PROTO_TO_HOST, &r).reason, FW_REASON_NONE);
        if (refusals++ == 0) {
            assert_int_equal(r.v[1], seqs[FW_TRAJ_CAPACITY]);
            assert_int_equal(r.v[2], FW_REASON_QUEUE_FULL);
        } else {
            assert_int_equal(r.v[1], seqs[FW_TRAJ_CAPACITY + 1]);
            assert_int_equal(r.v[2], FW_REASON_ORDER);
            assert_int_equal(r.v[5], seqs[FW_TRAJ_CAPACITY]);
        }
    }
    assert_int_equal(refusals, 2);
    run(100);
    /* Sent again, in order, under the same numbers. */
    from = F.tx_count;
    seq = seqs[FW_TRAJ_CAPACITY];
    for (int i = FW_TRAJ_CAPACITY; i < n; ++i) {
        rise_row(p, z0, i, n);
        traj_row(p, 20000, false, i == n - 1);
    }
    fw_poll(C);
    assert_int_equal(acks_since(from, TRAJ_FN), 2);
    assert_int_equal(now().traj_end_us, 20000u * (unsigned)n);
    ends_at(p);
}

/* The host stops sending: the controller reports an underrun, naming the rows it took (the one it
 * lacked is the next) the moment it starts to stop, and the row that comes late is refused
 * `ended` with how late it was.  By hand: rows 1 um apart (the slides at a few hundredths of a
 * mm/s) stop in the shortest stop, 20 ms, whose path takes half of it; with two setpoints of
 * margin the controller stops once the queue holds 12 ms of path or less, at 288 ms of the 300 ms
 * of 15 rows (the setpoint for 288 ms is computed one control period before it is due). */
static void test_underrun_is_reported_with_its_row_and_lateness(void **state)
{
    (void)state;
    double p[6];
    const double z0 = idle_at(p);
    unsigned from = F.tx_count;
    for (int i = 0; i < 15; ++i) {
        p[2] = (double)lround((z0 + 1e-6 * i) * 1e6) * 1e-6;
        traj_row(p, 20000, i == 0, false);
    }
    fw_poll(C);
    assert_int_equal(acks_since(from, TRAJ_FN), 15);
    const uint64_t t0 = F.now_us; /* the clock starts at the next control tick */
    proto_message end;
    while (!traj_end_since(from, &end) && F.now_us - t0 < 1000000u)
        one_ms();
    const double at_ms = (double)(F.now_us - t0) * 1e-3;
    if (fabs(at_ms - 288.0) > 3.0)
        fail_msg("the underrun was reported %.1f ms after the clock started, not 288", at_ms);
    assert_traj_end(from, FW_TRAJ_END_FAULT, FW_FAULT_UNDERRUN, 15);
    /* The 16th row, 37 ms later (the report went out with the poll after the tick that stopped). */
    for (int ms = 0; ms < 37; ++ms)
        one_ms();
    from = F.tx_count;
    p[2] = (double)lround((z0 + 15e-6) * 1e6) * 1e-6;
    traj_row(p, 20000, false, false);
    fw_poll(C);
    const proto_message r = reject_of(from, TRAJ_FN);
    assert_int_equal(r.v[2], FW_REASON_ENDED);
    assert_int_equal(r.v[5], FW_TRAJ_END_FAULT + 16 * FW_FAULT_UNDERRUN);
    if (r.v[6] < 37 || r.v[6] > 39)
        fail_msg("the late row was %d ms late, not 37 to 39", r.v[6]);
    assert_status_queue_empty(FW_STATE_FAULT);
    assert_int_equal(fw_fault_of(C), FW_FAULT_UNDERRUN);
}

/* A STOP from another host during a trajectory: the streaming host's rows still coming, during the
 * stop and once the controller is idle, are refused `ended` by a STOP and none starts a new
 * trajectory; TRAJ_END says a STOP ended it after the rows it took.  A row of no trajectory the
 * controller knows is refused `ended` (none); a first row starts one. */
static void test_rows_of_a_stopped_trajectory_never_start_another(void **state)
{
    (void)state;
    double p[6];
    unsigned from = streaming_then(30, PM_STOP, p);
    const uint64_t t_stop = F.now_us;
    run(10);
    assert_traj_end(from, FW_TRAJ_END_STOP, FW_FAULT_NONE, 30);
    for (int i = 0; i < 100 && fw_state_of(C) != FW_STATE_IDLE; ++i)
        run(10);
    assert_int_equal(fw_state_of(C), FW_STATE_IDLE);
    run(200);
    /* The streaming host goes on: rows of its trajectory reach an idle controller. */
    const uint64_t pulses = F.pulses;
    from = F.tx_count;
    const uint64_t since_ms = (F.now_us - t_stop) / 1000u;
    for (int i = 0; i < 3; ++i) {
        const proto_message r = row_after_end(p);
        assert_int_equal(r.v[5], FW_TRAJ_END_STOP);
        assert_true(r.v[6] >= (int32_t)since_ms - 1 && r.v[6] <= (int32_t)since_ms + 1);
    }
    run(100);
    assert_int_equal(fw_state_of(C), FW_STATE_IDLE);
    assert_true(F.pulses == pulses);
    assert_int_equal(acks_since(from, TRAJ_FN), 0);
    assert_int_equal(answers_since(from, TRAJ_FN), 3);
    /* A stranger's row: no trajectory of its identity ran. */
    traj_id = (uint8_t)(traj_id + 100u);
    const proto_message s = row_after_end(p);
    assert_int_equal(s.v[5], FW_TRAJ_END_NONE);
    assert_int_equal(s.v[6], 0);
    /* A first row starts a new one. */
    from = F.tx_count;
    memcpy(p, now().pose, sizeof p);
    traj_row(p, 50000, true, true);
    fw_poll(C);
    assert_int_equal(acks_since(from, TRAJ_FN), 1);
    assert_int_equal(fw_state_of(C), FW_STATE_MOVING);
}

/* An e-stop ends the trajectory at once; a row of it is refused `ended` by the e-stop fault, in
 * the e-stop state as in any other. */
static void test_estop_ends_the_trajectory(void **state)
{
    (void)state;
    double p[6];
    const unsigned from = streaming_then(20, PM_ESTOP, p);
    fw_poll(C);
    assert_traj_end(from, FW_TRAJ_END_FAULT, FW_FAULT_ESTOP, 20);
    const proto_message r = row_after_end(p);
    assert_int_equal(r.v[5], FW_TRAJ_END_FAULT + 16 * FW_FAULT_ESTOP);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_stop_drops_queue),
        cmocka_unit_test(test_stop_during_a_rows_validation_refuses_it_ended),
        cmocka_unit_test(test_row_in_the_hand_over_when_the_tick_ends_it_is_refused_ended),
        cmocka_unit_test(test_fault_drops_queue),
        cmocka_unit_test(test_stop_in_fault_drops_queue),
        cmocka_unit_test(test_estop_drops_queue),
        cmocka_unit_test(test_underrun_drops_queue),
        cmocka_unit_test(test_first_rows_wait_for_the_lead),
        cmocka_unit_test(test_last_row_or_full_queue_starts_the_clock),
        cmocka_unit_test(test_rows_after_a_full_queue_wait_their_turn),
        cmocka_unit_test(test_underrun_is_reported_with_its_row_and_lateness),
        cmocka_unit_test(test_rows_of_a_stopped_trajectory_never_start_another),
        cmocka_unit_test(test_estop_ends_the_trajectory),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
