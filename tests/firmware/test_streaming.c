/* The end of a streamed trajectory: once a stop, a fault, an underrun or an e-stop ends it, no
 * point is taken for it any more, and at rest its queue is empty (depth 0, the whole capacity
 * free, in STATUS and in acknowledgements); a new trajectory then starts from the rest pose. */
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

/* Stages p and commits it as a trajectory point dt_us after the previous one. */
static void point(const double p[6], uint32_t dt_us, bool last)
{
    const uint8_t s = seq++;
    stage(s, p);
    const int32_t v[3] = {s, (int32_t)dt_us, last ? 1 : 0};
    send(PM_TRAJ_COMMIT, v);
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
    memcpy(p, C.pose, sizeof p);
    const unsigned from = F.tx_count;
    for (unsigned i = 0; i < n; ++i) {
        p[2] += 0.001;
        point(p, 50000, false);
    }
    fw_poll(&C);
    assert_int_equal(acks_since(from, TRAJ_FN), n);
    run(300);
    assert_int_equal(C.state, FW_STATE_MOVING);
    assert_true(fw_traj_depth(&C.traj) > n / 3);
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

static void test_stop_drops_queue(void **state)
{
    (void)state;
    reach(FW_STATE_IDLE);
    stream_and_go(30);
    cmd(PM_STOP);
    run(10);
    assert_int_equal(C.state, FW_STATE_STOPPING);
    /* Nothing more is taken for the stopping trajectory, and the refusal says why. */
    unsigned from = F.tx_count;
    double more[6];
    memcpy(more, C.traj.tail.pose, sizeof more);
    more[2] += 0.001;
    point(more, 50000, false);
    fw_poll(&C);
    const proto_message r = reject_of(from, TRAJ_FN);
    assert_int_equal(r.v[2], FW_REASON_STATE);
    assert_int_equal(r.v[5], FW_STATE_STOPPING);
    for (int i = 0; i < 100 && C.state == FW_STATE_STOPPING; ++i)
        run(10);
    assert_int_equal(C.state, FW_STATE_IDLE);
    assert_int_equal(C.fault, FW_FAULT_NONE);
    assert_int_equal(fw_traj_depth(&C.traj), 0);
    assert_status_queue_empty(FW_STATE_IDLE);

    /* A new trajectory runs from where the robot stopped, on a clock from zero: ten points
     * 0.5 mm down each, the last flagged, ending on the last point to the step. */
    double p[6], rest[6];
    memcpy(rest, C.pose, sizeof rest);
    memcpy(p, rest, sizeof p);
    from = F.tx_count;
    for (int i = 1; i <= 10; ++i) {
        p[2] = (double)lround((rest[2] - 0.0005 * i) * 1e6) * 1e-6; /* as the wire carries it */
        point(p, 50000, i == 10);
    }
    fw_poll(&C);
    assert_int_equal(acks_since(from, TRAJ_FN), 10);
    assert_int_equal(fw_traj_end_us(&C.traj), 500000);
    for (int i = 0; i < 200 && C.state != FW_STATE_IDLE; ++i)
        run(10);
    assert_int_equal(C.state, FW_STATE_IDLE);
    assert_int_equal(C.fault, FW_FAULT_NONE);
    for (int k = 0; k < 6; ++k)
        assert_true(fabs(C.pose[k] - p[k]) < 1e-9);
    tse_ik_result ik;
    assert_int_equal(tse_ik(&C.geom, p, NULL, &ik), TSE_OK);
    for (int k = 0; k < 6; ++k)
        assert_int_equal(F.steps[k], lround(ik.q[k] * 1280000.0));
    assert_status_queue_empty(FW_STATE_IDLE);
}

/* The host falls silent while streaming: a controlled stop, the fault latched, the queue gone. */
static void test_fault_drops_queue(void **state)
{
    (void)state;
    reach(FW_STATE_IDLE);
    stream_and_go(30);
    for (int i = 0; i < 100 && C.state != FW_STATE_FAULT; ++i)
        fake_run(&F, &C, 10); /* no heartbeat */
    assert_int_equal(C.state, FW_STATE_FAULT);
    assert_int_equal(C.fault, FW_FAULT_WATCHDOG);
    assert_int_equal(fw_traj_depth(&C.traj), 0);
    assert_int_equal(fw_traj_free(&C.traj), FW_TRAJ_CAPACITY);
    assert_status_queue_empty(FW_STATE_FAULT);
}

/* A STOP at rest ends whatever trajectory is still held: here one left in the queue behind the
 * controller's back, as the fault latch used to. */
static void test_stop_in_fault_drops_queue(void **state)
{
    (void)state;
    reach(FW_STATE_FAULT);
    tse_ik_result ik;
    assert_int_equal(tse_ik(&C.geom, C.geom.home_pose, NULL, &ik), TSE_OK);
    fw_traj_start(&C.traj, &C.lim, C.geom.home_pose, ik.q);
    double p[6];
    memcpy(p, C.geom.home_pose, sizeof p);
    fw_plan_result why;
    p[2] += 1e-5;
    assert_int_equal(fw_traj_push(&C.traj, &C.geom, &C.lim, p, 50000, false, &why), 0);
    assert_int_equal(fw_traj_depth(&C.traj), 1);
    const unsigned from = F.tx_count;
    cmd(PM_STOP);
    fw_poll(&C);
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
    fw_poll(&C);
    assert_int_equal(C.state, FW_STATE_ESTOP);
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
    for (int i = 0; i < 200 && C.state != FW_STATE_FAULT; ++i)
        run(10);
    assert_int_equal(C.state, FW_STATE_FAULT);
    assert_int_equal(C.fault, FW_FAULT_UNDERRUN);
    assert_status_queue_empty(FW_STATE_FAULT);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_stop_drops_queue),
        cmocka_unit_test(test_fault_drops_queue),
        cmocka_unit_test(test_stop_in_fault_drops_queue),
        cmocka_unit_test(test_estop_drops_queue),
        cmocka_unit_test(test_underrun_drops_queue),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
