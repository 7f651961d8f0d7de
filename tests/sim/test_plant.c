/* The firmware against the simulator's plant, without a bus: homing from power-up, moves,
 * blends, stops, an e-stop and a timed trajectory must never break a physical invariant (stroke,
 * speed, acceleration, pulse timing), and the plate must end on its targets (10 um, 1e-5 rad). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "fake_hal.h"
#include "fw/controller.h"
#include "hal_posix/plant.h"

static fake_hal F;
static fw_controller C;
static tse_plant P;
static uint8_t seq = 1;

static void run(uint32_t ms)
{
    for (uint32_t m = 0; m < ms; ++m) {
        if (m % 10 == 0) {
            proto_message hb = {PM_HOST_HEARTBEAT, 1, {0}};
            hal_can_frame f;
            proto_encode(&hb, &f);
            fake_send(&F, f.id, f.len, f.data);
        }
        F.tx_count = 0;
        fw_poll(&C);
        fw_control_tick(&C);
        for (int t = 0; t < 100; ++t) {
            fw_step_tick(&C);
            plant_tick(&P);
        }
        F.now_us += 1000;
        if (P.breaches)
            fail_msg("plant: %s (state %d src %d stopping %d tau %.4f of %.4f, homing %d phase %d fault %d depth %u)", P.first_breach,
                     C.state, C.src, C.stopping, (double)C.tau, (double)C.move.prof.T, C.home.active, C.home.phase, C.fault, C.traj.count);
    }
}

static void send(proto_msg m, const int32_t *v)
{
    fake_send_msg(&F, 1, m, v);
}

static void cmd(proto_msg m)
{
    const int32_t v[1] = {seq++};
    send(m, v);
}

static void move_to(const double p[6], int32_t ms)
{
    const uint8_t s = seq++;
    const int32_t a[3] = {s, (int32_t)lround(p[0] * 1e6), (int32_t)lround(p[1] * 1e6)};
    const int32_t b[3] = {s, (int32_t)lround(p[2] * 1e6), (int32_t)lround(p[3] * 1e6)};
    const int32_t c[3] = {s, (int32_t)lround(p[4] * 1e6), (int32_t)lround(p[5] * 1e6)};
    const int32_t m[3] = {s, 0, ms};
    send(PM_POSE_A, a);
    send(PM_POSE_B, b);
    send(PM_POSE_C, c);
    send(PM_MOVE_COMMIT, m);
    run(5); /* the commit is taken at the next poll */
}

static void wait_idle(uint32_t max_ms)
{
    for (uint32_t t = 0; t < max_ms && !(C.state == FW_STATE_IDLE && C.src == FW_SRC_NONE); t += 50) {
        run(50);
        if (getenv("TSE_DEBUG") && t % 1000 == 0)
            print_message("t %u state %d src %d run %u queued %u running %d sgtick %u\n", t, C.state, C.src, C.segments_run,
                          stepgen_queued(&C.sg), C.sg.running, C.sg.tick);
    }
    run(20);
    if (C.state != FW_STATE_IDLE)
        print_message("stuck: state %d src %d tau %.4f T %.4f segs %u run %u queued %u stopping %d has_next %d fault %d\n",
                      C.state, C.src, (double)C.tau, (double)C.move.prof.T, C.move.segments, C.segments_run,
                      stepgen_queued(&C.sg), C.stopping, C.has_next, C.fault);
    assert_int_equal(C.state, FW_STATE_IDLE);
}

static void assert_pose(const double want[6])
{
    assert_true(plant_update_pose(&P));
    for (int k = 0; k < 3; ++k)
        if (fabs(P.pose[k] - want[k]) > 10e-6)
            fail_msg("position %d: %.9f vs %.9f", k, P.pose[k], want[k]);
    for (int k = 3; k < 6; ++k)
        if (fabs(P.pose[k] - want[k]) > 1e-5)
            fail_msg("angle %d: %.9f vs %.9f", k, P.pose[k], want[k]);
}

static void start(double at)
{
    fw_hal hal;
    fake_hal_init(&F, &hal);
    const fw_config cfg = {1, 1000, 100000};
    /* The plant takes over the stepper and the inputs; the bus, clock and storage stay fake. */
    hal.stepper = plant_stepper(&P);
    hal.inputs = plant_inputs(&P);
    assert_int_equal(fw_init(&C, &hal, &cfg), 0);
    const double s0[6] = {at, at, at, at, at, at};
    const plant_config pc = {(double)C.params.v[FP_STEPS_PER_M], C.params.v[FP_SLIDE_VMAX] * 1e-6,
                             C.params.v[FP_SLIDE_AMAX] * 1e-6, 0.05, 100000, C.sg.cfg.min_step_interval,
                             C.sg.cfg.dir_setup_ticks};
    plant_init(&P, &pc, &C.geom, s0);
    cmd(PM_ENABLE);
    run(20);
    cmd(PM_HOME);
    run(20);
    for (int t = 0; t < 120000 && C.state == FW_STATE_HOMING; t += 100)
        run(100);
    assert_int_equal(C.state, FW_STATE_IDLE);
    assert_true(C.homed);
    assert_pose(C.geom.home_pose);
}

static void test_moves_land_within_tolerance(void **state)
{
    (void)state;
    start(0.05);
    const double targets[][6] = {
        {0.1, -0.05, 1.1, 0.1, -0.05, 0.2},
        {-0.15, 0.1, 0.7, -0.05, 0.08, -0.3},
        {0.0, 0.0, 1.45, 0.0, 0.0, 0.0},
        {0.2, 0.15, 0.9, 0.0, 0.1, 0.5},
    };
    for (size_t i = 0; i < sizeof targets / sizeof targets[0]; ++i) {
        move_to(targets[i], 800);
        wait_idle(30000);
        assert_pose(targets[i]);
    }
}

static void test_blend_stop_and_estop_keep_invariants(void **state)
{
    (void)state;
    start(0.3);
    const double a[6] = {0.08, 0, 1.0, 0, 0, 0.1}, b[6] = {0.08, 0.1, 1.1, 0.05, 0, 0}, c[6] = {-0.1, 0, 0.8, 0, 0, 0};
    move_to(a, 1500);
    run(300);
    move_to(b, 1500);
    wait_idle(30000);
    assert_pose(b);
    move_to(c, 3000);
    run(1200);
    cmd(PM_STOP);
    wait_idle(5000); /* a controlled stop along the path, within the limits */
    move_to(a, 2000);
    run(700);
    cmd(PM_ESTOP);
    run(200);
    assert_int_equal(C.state, FW_STATE_ESTOP);
}

static void test_trajectory(void **state)
{
    (void)state;
    start(0.05);
    /* A circle of 3 cm radius at 1.1 m, streamed as points every 20 ms over 10 s, eased in and out
     * (the slides move several times faster than the plate does sideways). */
    const double z = 1.1;
    const int n = 500;
    double last[6] = {0};
    for (int i = 1; i <= n; ++i) {
        const double s = (double)i / n, e = 10 * pow(s, 3) - 15 * pow(s, 4) + 6 * pow(s, 5);
        const double ang = 2 * TSE_PI * e;
        const double p[6] = {0.03 * sin(ang), 0.03 * (1 - cos(ang)), z, 0, 0, 0};
        const uint8_t sq = seq++;
        const int32_t A[3] = {sq, (int32_t)lround(p[0] * 1e6), (int32_t)lround(p[1] * 1e6)};
        const int32_t B[3] = {sq, (int32_t)lround(p[2] * 1e6), 0};
        const int32_t Cc[3] = {sq, 0, 0};
        const int32_t T[3] = {sq, i == 1 ? 2000000 : 20000, i == n};
        send(PM_POSE_A, A);
        send(PM_POSE_B, B);
        send(PM_POSE_C, Cc);
        send(PM_TRAJ_COMMIT, T);
        memcpy(last, p, sizeof last);
        /* Flow control: keep the queue nearly full, as a host streaming against queue_free would. */
        while (C.traj.count > 24)
            run(5);
        run(1);
        if (getenv("TSE_DEBUG") && i % 10 == 0)
            print_message("i %d count %u tau %.3f end %.3f state %d\n", i, C.traj.count, (double)C.tau,
                          (double)fw_traj_end_us(&C.traj) * 1e-6, C.state);
        if (fw_traj_end_us(&C.traj) != 2000000u + 20000u * (uint64_t)(i - 1)) {
            const hal_can_frame *r = fake_last(&F, 0x03, 0);
            fail_msg("point %d refused: reason %d, kinematic status %d, scissor %d", i, r ? r->data[2] : -1,
                     r ? r->data[4] : -1, r ? r->data[3] : -1);
        }
        assert_int_not_equal(C.state, FW_STATE_FAULT);
    }
    wait_idle(10000);
    for (int k = 0; k < 6; ++k)
        last[k] = (double)lround(last[k] * 1e6) * 1e-6; /* the wire's resolution */
    assert_pose(last);
}

/* A host that stops streaming mid-way: the robot stops along the queued path within every limit,
 * and latches the underrun. */
static void test_underrun_stops_smoothly(void **state)
{
    (void)state;
    start(0.05);
    for (int i = 1; i <= 100; ++i) {
        const double p[6] = {0.0005 * i, 0.0, 1.1, 0, 0, 0};
        const uint8_t sq = seq++;
        const int32_t A[3] = {sq, (int32_t)lround(p[0] * 1e6), 0}, B[3] = {sq, 1100000, 0}, Cc[3] = {sq, 0, 0};
        const int32_t T[3] = {sq, i == 1 ? 1000000 : 20000, 0};
        send(PM_POSE_A, A);
        send(PM_POSE_B, B);
        send(PM_POSE_C, Cc);
        send(PM_TRAJ_COMMIT, T);
        run(1);
    }
    for (int t = 0; t < 6000 && C.state != FW_STATE_FAULT; t += 10)
        run(10); /* run() fails the test on any breach */
    assert_int_equal(C.state, FW_STATE_FAULT);
    assert_int_equal(C.fault, FW_FAULT_UNDERRUN);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_moves_land_within_tolerance),
        cmocka_unit_test(test_blend_stop_and_estop_keep_invariants),
        cmocka_unit_test(test_trajectory),
        cmocka_unit_test(test_underrun_stops_smoothly),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
