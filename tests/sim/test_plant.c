/* The firmware against the simulator's plant, without a bus: homing from power-up (below and above
 * the switches), moves, blends, stops, an e-stop and a timed trajectory must never break a
 * physical invariant (stroke, speed, acceleration, pulse timing), and the plate must end on its
 * targets (10 um, 1e-5 rad).  Homing must honour each switch's position and take the time of its
 * distances at the homing speed; once homed, the switches catch lost steps.  And the plant's own
 * switch and timing checks, alone. */
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
#include "fw/inspect.h"
#include "fw/runtime.h"
#include "hal_posix/plant.h"

static fake_hal F;
static fw_controller_mem C_mem;
static fw_controller *C;
static tse_plant P;
static uint8_t seq = 1;
static uint32_t homing_ms;  /* simulated time spent in HOMING by the last start() */
static double lowest[6];    /* lowest true slide positions since start() [m] */

static fw_inspection now(void)
{
    fw_inspection i;
    fw_inspect(C, &i);
    return i;
}

/* The plant takes each step tick; the time in HOMING is counted at each control tick. */
static void ran(void *ctx, fw_ran what)
{
    (void)ctx;
    if (what == FW_RAN_STEP)
        plant_tick(&P);
    else if (what == FW_RAN_CONTROL && fw_state_of(C) == FW_STATE_HOMING)
        ++homing_ms;
}

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
        fw_run_period(C, ran, NULL);
        F.now_us += 1000;
        for (int k = 0; k < 6; ++k)
            if ((double)P.steps[k] / 1280000.0 < lowest[k])
                lowest[k] = (double)P.steps[k] / 1280000.0;
        if (P.breaches)
            fail_msg("plant: %s (state %d src %d stopping %d tau %.4f of %.4f, homing %d phase %d fault %d depth %u)", P.first_breach,
                     fw_state_of(C), now().src, now().stopping, (double)now().tau, (double)now().move.prof.T, now().home_active, now().home_phase, fw_fault_of(C), now().traj_depth);
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
    for (uint32_t t = 0; t < max_ms && !(fw_state_of(C) == FW_STATE_IDLE && now().src == FW_SRC_NONE); t += 50) {
        run(50);
        if (getenv("TSE_DEBUG") && t % 1000 == 0)
            print_message("t %u state %d src %d run %u queued %u running %d sgtick %u\n", t, fw_state_of(C), now().src, now().segments_run,
                          stepgen_queued(fw_stepgen_of(C)), fw_stepgen_of(C)->running, fw_stepgen_of(C)->tick);
    }
    run(20);
    if (fw_state_of(C) != FW_STATE_IDLE)
        print_message("stuck: state %d src %d tau %.4f T %.4f segs %u run %u queued %u stopping %d has_next %d fault %d\n",
                      fw_state_of(C), now().src, (double)now().tau, (double)now().move.prof.T, now().move.segments, now().segments_run,
                      stepgen_queued(fw_stepgen_of(C)), now().stopping, now().has_next, fw_fault_of(C));
    assert_int_equal(fw_state_of(C), FW_STATE_IDLE);
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

/* The controller, its switches moved to sw_um (NULL: the defaults) by PARAM_SET while disabled,
 * and the plant built from its parameters, the slides at s0. */
static void boot(const double s0[6], const int32_t *sw_um)
{
    fw_hal hal;
    fake_hal_init(&F, &hal);
    const fw_config cfg = {1, 1000, 100000, NULL, NULL, NULL};
    /* The plant takes over the stepper and the inputs; the bus, clock and storage stay fake. */
    hal.stepper = plant_stepper(&P);
    hal.inputs = plant_inputs(&P);
    C = fw_init(&C_mem, &hal, &cfg);
    assert_non_null(C);
    for (int k = 0; sw_um && k < 6; ++k) {
        const int32_t v[2] = {FP_HOME_SW_1 + k, sw_um[k]};
        send(PM_PARAM_SET, v);
        fw_poll(C); /* no step tick: the plant is not built yet */
        assert_int_equal(fw_params_of(C)->v[FP_HOME_SW_1 + k], sw_um[k]);
    }
    plant_config pc = {(double)fw_params_of(C)->v[FP_STEPS_PER_M], fw_params_of(C)->v[FP_SLIDE_VMAX] * 1e-6,
                       fw_params_of(C)->v[FP_SLIDE_AMAX] * 1e-6, 0.05, 100000, fw_stepgen_of(C)->cfg.min_step_interval,
                       (uint32_t)fw_params_of(C)->v[FP_STEP_PULSE_NS], (uint32_t)fw_params_of(C)->v[FP_DIR_SETUP_NS], {0}};
    for (int k = 0; k < 6; ++k)
        pc.home_sw[k] = fw_params_of(C)->v[FP_HOME_SW_1 + k] * 1e-6;
    const plant_kinematics pk = plant_kinematics_of(&fw_geometry_of(C)->p);
    assert_int_equal(plant_init(&P, &pc, &pk, s0), 0);
    for (int k = 0; k < 6; ++k)
        lowest[k] = s0[k];
}

/* Enables and homes; the controller's slide coordinates must then be the plant's true positions
 * to the step, and the plate at the home pose. */
static void homing(void)
{
    cmd(PM_ENABLE);
    run(20);
    homing_ms = 0;
    cmd(PM_HOME);
    run(20);
    for (int t = 0; t < 120000 && fw_state_of(C) == FW_STATE_HOMING; t += 100)
        run(100);
    assert_int_equal(fw_state_of(C), FW_STATE_IDLE);
    assert_true(fw_homed_of(C));
    int32_t count[6];
    stepgen_positions(fw_stepgen_of(C), count);
    for (int k = 0; k < 6; ++k)
        if (llabs((long long)count[k] - (long long)P.steps[k]) > 1)
            fail_msg("slide %d: the controller counts %d steps, the slide is at %lld", k + 1, count[k],
                     (long long)P.steps[k]);
    assert_pose(fw_geometry_of(C)->home_pose);
}

static void start(double at)
{
    const double s0[6] = {at, at, at, at, at, at};
    boot(s0, NULL);
    homing();
}

/* Moves the slide by `steps` behind the controller's back (lost steps), its position history
 * along with it, so that the plant's acceleration measure sees no jump. */
static void shift(int k, int64_t steps)
{
    P.steps[k] += steps;
    for (int j = 0; j < 20; ++j)
        P.hist[j][k] += steps;
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
    assert_int_equal(fw_state_of(C), FW_STATE_ESTOP);
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
    uint8_t id = 0; /* the trajectory's identity: its first row's number */
    for (int i = 1; i <= n; ++i) {
        const double s = (double)i / n, e = 10 * pow(s, 3) - 15 * pow(s, 4) + 6 * pow(s, 5);
        const double ang = 2 * TSE_PI * e;
        const double p[6] = {0.03 * sin(ang), 0.03 * (1 - cos(ang)), z, 0, 0, 0};
        const uint8_t sq = seq++;
        const int32_t A[3] = {sq, (int32_t)lround(p[0] * 1e6), (int32_t)lround(p[1] * 1e6)};
        const int32_t B[3] = {sq, (int32_t)lround(p[2] * 1e6), 0};
        const int32_t Cc[3] = {sq, 0, 0};
        if (i == 1)
            id = sq;
        const int32_t T[4] = {sq, i == 1 ? 2000000 : 20000, (i == 1 ? (int32_t)PROTO_TRAJ_FIRST : 0) | (i == n ? (int32_t)PROTO_TRAJ_LAST : 0), id};
        send(PM_POSE_A, A);
        send(PM_POSE_B, B);
        send(PM_POSE_C, Cc);
        send(PM_TRAJ_COMMIT, T);
        memcpy(last, p, sizeof last);
        /* Flow control: keep the queue nearly full, as a host streaming against queue_free would. */
        while (now().traj_depth > 24)
            run(5);
        run(1);
        if (getenv("TSE_DEBUG") && i % 10 == 0)
            print_message("i %d count %u tau %.3f end %.3f state %d\n", i, now().traj_depth, (double)now().tau,
                          (double)now().traj_end_us * 1e-6, fw_state_of(C));
        if (now().traj_end_us != 2000000u + 20000u * (uint64_t)(i - 1)) {
            const hal_can_frame *r = fake_last(&F, 0x03, 0);
            fail_msg("point %d refused: reason %d, kinematic status %d, scissor %d", i, r ? r->data[2] : -1,
                     r ? r->data[4] : -1, r ? r->data[3] : -1);
        }
        assert_int_not_equal(fw_state_of(C), FW_STATE_FAULT);
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
    uint8_t id = 0;
    for (int i = 1; i <= 100; ++i) {
        const double p[6] = {0.0005 * i, 0.0, 1.1, 0, 0, 0};
        const uint8_t sq = seq++;
        const int32_t A[3] = {sq, (int32_t)lround(p[0] * 1e6), 0}, B[3] = {sq, 1100000, 0}, Cc[3] = {sq, 0, 0};
        if (i == 1)
            id = sq;
        const int32_t T[4] = {sq, i == 1 ? 1000000 : 20000, i == 1 ? (int32_t)PROTO_TRAJ_FIRST : 0, id};
        send(PM_POSE_A, A);
        send(PM_POSE_B, B);
        send(PM_POSE_C, Cc);
        send(PM_TRAJ_COMMIT, T);
        run(1);
    }
    for (int t = 0; t < 6000 && fw_state_of(C) != FW_STATE_FAULT; t += 10)
        run(10); /* run() fails the test on any breach */
    assert_int_equal(fw_state_of(C), FW_STATE_FAULT);
    assert_int_equal(fw_fault_of(C), FW_FAULT_UNDERRUN);
}

/* The homing time of the defaults (homing_speed 20 mm/s, slide_amax 1 m/s^2, of which homing
 * ramps take 90 %, homing_backoff 2 mm, slide_vmax 0.15 m/s, switches at 0.2 m), derived from the
 * distances: `travel` [m] at the homing speed, plus
 *   - ramps: up to four starts and stops, each costing at most v / a = 20 ms;
 *   - the creep back over the braking distance v^2 / (2 0.9 a) = 0.22 mm plus half a millimetre of
 *     read-out lag and hysteresis, at no less than 1/64 of the homing speed (0.3125 mm/s): 2.3 s;
 *   - the joint move to home_s over d_home [m] at 90 % of the slide speed limit, which at this
 *     test's 100 kHz step interrupt is the step generator's: 99 steps per 1 ms segment (a tick of
 *     DIR set-up off the 100), 90 % of it planned, 0.9 * 99000 / 1.28e6 = 0.0696 m/s (below
 *     slide_vmax); plus 0.15 s of ramps and 0.2 s for its jerk limit;
 *   - 0.1 s of command latency.
 * Creeping the whole way, as homing once did from below a switch, would take travel / 0.3125 mm/s:
 * minutes. */
#define SLIDE_VMAX_100KHZ (0.9 * 99000.0 / 1280000.0)

static double homing_bound_s(double travel, double d_home)
{
    const double v = 0.02, creep = v / 64.0;
    return travel / v + 4 * 0.02 + (v * v / (2 * 0.9) + 0.5e-3) / creep + d_home / (0.9 * SLIDE_VMAX_100KHZ) +
           0.15 + 0.2 + 0.1;
}

/* From below the switches (tse-sim's default start, 0.05 m): up 15 cm past them, back, and the
 * edge; the coordinates are the true ones (homing() checks), in the time of the distances. */
static void test_homing_from_below(void **state)
{
    (void)state;
    start(0.05);
    const double t = homing_ms * 1e-3, d_home = fw_geometry_of(C)->home_s - 0.2;
    const double bound = homing_bound_s(0.2 - 0.05 + 2 * 0.002, d_home);
    print_message("homing from 0.05 m: %.2f s (bound %.2f s, at the creep speed %.0f s)\n", t, bound,
                  0.15 / (0.02 / 64));
    assert_true(t <= bound);
    /* And no faster than the homing speed and the slide speed limit allow. */
    assert_true(t >= 0.15 / 0.02 + d_home / SLIDE_VMAX_100KHZ);
    /* The slides did go up and come back: none was ever left below where it started. */
    for (int k = 0; k < 6; ++k)
        assert_true(lowest[k] >= 0.05 - 1e-9);
}

/* From above, with every switch somewhere else: each slide's coordinate is set at its own switch
 * (homing() checks the coordinates against the true positions, to the step: a switch taken for
 * another's would be centimetres off), in the time of the longest seek. */
static void test_homing_from_above_own_switches(void **state)
{
    (void)state;
    const int32_t sw[6] = {190000, 210000, 230000, 250000, 270000, 200000};
    const double s0[6] = {0.3, 0.3, 0.3, 0.3, 0.3, 0.3};
    boot(s0, sw);
    homing();
    const double t = homing_ms * 1e-3;
    const double bound = homing_bound_s(0.3 - 0.19, fw_geometry_of(C)->home_s - 0.19);
    print_message("homing from 0.3 m: %.2f s (bound %.2f s)\n", t, bound);
    assert_true(t <= bound);
    assert_true(t >= (0.3 - 0.19) / 0.02 + (fw_geometry_of(C)->home_s - 0.19) / SLIDE_VMAX_100KHZ);
    /* Each slide went down to its own switch, and not beyond it by more than the braking
     * distance (0.22 mm) and the read-out lag. */
    for (int k = 0; k < 6; ++k) {
        assert_true(lowest[k] <= sw[k] * 1e-6);
        assert_true(lowest[k] >= sw[k] * 1e-6 - 0.5e-3);
    }
}

/* The geometry of the controller's default parameters. */
static void default_geometry(tse_geometry *g)
{
    fw_param_set ps;
    fw_params_default(&ps);
    tse_params kp;
    fw_params_kinematics(&ps, &kp);
    assert_int_equal(tse_geometry_init(g, &kp), TSE_PARAM_OK);
}

/* Lost steps, simulated by moving a slide 5 mm behind the controller's back: slide 1, homed 2 mm
 * above its switch, pushed down to 3 mm below it (its switch pressed while the count says above);
 * then slide 2, homed 2 mm below its switch, pushed up past it.  Each is a limit fault, the zero
 * dropped; before the push, no fault. */
static void test_lost_steps_fault(void **state)
{
    (void)state;
    tse_geometry g;
    default_geometry(&g);
    const int32_t home_um = (int32_t)lround(g.home_s * 1e6);
    for (int slide = 0; slide < 2; ++slide) {
        int32_t sw[6] = {200000, 200000, 200000, 200000, 200000, 200000};
        sw[slide] = slide == 0 ? home_um - 2000 : home_um + 2000;
        const double s0[6] = {0.05, 0.05, 0.05, 0.05, 0.05, 0.05};
        boot(s0, sw);
        homing();
        run(200);
        assert_int_equal(fw_state_of(C), FW_STATE_IDLE);
        shift(slide, slide == 0 ? -6400 : 6400); /* 5 mm */
        run(10);
        assert_int_equal(fw_state_of(C), FW_STATE_FAULT);
        assert_int_equal(fw_fault_of(C), FW_FAULT_LIMIT);
        assert_false(fw_homed_of(C));
    }
}

/* Legitimate motion below the switches: a pose that puts slide 2 at 14 mm (tse-kin ik), far below
 * its 0.2 m switch, and back; no fault, and the slide did go there. */
static void test_motion_below_switch(void **state)
{
    (void)state;
    start(0.3);
    const double low[6] = {0.2, 0.15, 0.9, 0.0, 0.1, 0.5};
    move_to(low, 1500);
    wait_idle(30000);
    assert_pose(low);
    assert_true(lowest[1] < 0.2 - 0.1);
    assert_int_equal(fw_fault_of(C), FW_FAULT_NONE);
    move_to(fw_geometry_of(C)->home_pose, 1500);
    wait_idle(30000);
    assert_int_equal(fw_fault_of(C), FW_FAULT_NONE);
    assert_true(fw_homed_of(C));
}

/* The plant's switches and timing checks on their own, at 100 kHz (10 us ticks). */
static void test_plant_switches_and_timing(void **state)
{
    (void)state;
    tse_geometry g;
    default_geometry(&g);
    const plant_config pc = {1280000.0, 0.15, 1.0, 0.05, 100000, 1, 2000, 15000, {0.2, 0.2, 0.2, 0.2, 0.2, 0.2}};
    /* Slide 1 on its switch's last pressed step (0.2 m = 256000 steps), slide 2 a step above,
     * slide 3 a step beyond the high end (0.9 m). */
    const double s0[6] = {0.2, 0.2 + 1 / 1280000.0, 0.9 + 1 / 1280000.0, 0.3, 0.3, 0.3};
    const plant_kinematics pk = plant_kinematics_of(&g.p);
    assert_int_equal(plant_init(&P, &pc, &pk, s0), 0);
    const hal_inputs in = plant_inputs(&P);
    const hal_stepper st = plant_stepper(&P);
    const uint16_t m = in.limits(in.ctx);
    assert_int_equal(m & 0x3F, 0x01);
    assert_int_equal(m >> 8, 0x04);
    assert_int_equal(P.pulse_ns, 2000);
    assert_int_equal(P.dir_setup_ns, 15000);
    st.enable(st.ctx, true);
    plant_tick(&P);
    /* DIR set-up 15 us: a step one tick (10 us) after the change is too soon, two ticks are not. */
    st.set_dir(st.ctx, 0x3F & ~0x08);
    plant_tick(&P);
    st.pulse(st.ctx, 0x08);
    assert_int_equal(P.breaches, PLANT_DIR_SETUP);
    P.breaches = 0;
    st.set_dir(st.ctx, 0x3F & ~0x08 & ~0x10);
    plant_tick(&P);
    plant_tick(&P);
    st.pulse(st.ctx, 0x10);
    assert_int_equal(P.breaches, 0);
    /* 2 us high and 2 us low fit between steps on consecutive ticks; 6 us and 6 us do not. */
    plant_tick(&P);
    st.pulse(st.ctx, 0x20);
    plant_tick(&P);
    st.pulse(st.ctx, 0x20);
    assert_int_equal(P.breaches, 0);
    st.timing(st.ctx, 6000, 15000);
    assert_int_equal(P.pulse_ns, 6000);
    assert_int_equal(P.timing_calls, 1);
    plant_tick(&P);
    st.pulse(st.ctx, 0x20);
    assert_int_equal(P.breaches, PLANT_PULSE_SPACING);
    P.breaches = 0;
    /* DIR of an axis changed while its STEP is still high (6 us after the edge). */
    plant_tick(&P);
    plant_tick(&P);
    st.pulse(st.ctx, 0x01);
    st.set_dir(st.ctx, P.forward ^ 0x01);
    assert_int_equal(P.breaches, PLANT_DIR_SETUP);
}

/* The drivers' timing reaches the plant through the controller: a PARAM_SET of the pulse width is
 * programmed, and what the plant checks from then on. */
static void test_timing_reaches_plant(void **state)
{
    (void)state;
    const double s0[6] = {0.3, 0.3, 0.3, 0.3, 0.3, 0.3};
    boot(s0, NULL);
    const uint32_t calls = P.timing_calls;
    const int32_t v[2] = {FP_STEP_PULSE_NS, 3500};
    send(PM_PARAM_SET, v);
    run(5);
    assert_int_equal(P.timing_calls, calls + 1);
    assert_int_equal(P.pulse_ns, 3500);
    assert_int_equal(P.dir_setup_ns, 5000);
    homing(); /* and the firmware keeps within it */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_moves_land_within_tolerance),
        cmocka_unit_test(test_blend_stop_and_estop_keep_invariants),
        cmocka_unit_test(test_trajectory),
        cmocka_unit_test(test_underrun_stops_smoothly),
        cmocka_unit_test(test_homing_from_below),
        cmocka_unit_test(test_homing_from_above_own_switches),
        cmocka_unit_test(test_lost_steps_fault),
        cmocka_unit_test(test_motion_below_switch),
        cmocka_unit_test(test_plant_switches_and_timing),
        cmocka_unit_test(test_timing_reaches_plant),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
