/* The whole controller (fw/controller.h) on the emulated Cortex-M4F, in float, at the board's
 * rates (1 kHz control segments, 200 kHz step interrupts), driven through its CAN interface by a
 * scripted host.
 *
 * In RAM, in place of the board's peripherals:
 * - a CAN loopback: hal_can over two rings, the frames the host script sends and the frames the
 *   controller answers; the script encodes and decodes them with the firmware's codec (fw/proto.h,
 *   the protocol's single source) and sees the controller only through them;
 * - a plant: six slides that integrate the STEP pulses with the DIR pins (in steps from s = 0,
 *   which the controller does not know before homing), homing switches pressed for
 *   s <= home_sw_k (the parameter values the script set, compared in integers), the shared ENABLE,
 *   the e-stop input, a microsecond clock;
 * - one context for all (fw/runtime.h): every millisecond fw_period_start (the thread's poll,
 *   then the control tick), then 200 fw_step_tick; the e-stop input's interrupt (EXTI on the
 *   board) calls fw_estop_isr between two step ticks.
 *
 * Script: status every 10 ms and two homing switches moved (PARAM_SET, while disabled); ENABLE;
 * HOME (slides starting above, on and below-but-near their switches); a move to a pose (ACK with
 * its duration, STATUS MOVING then IDLE, the plant's slides on the double-precision IK slides of
 * the pose within a few steps, telemetry agreeing with the plant); a second move stopped with
 * STOP half-way (STATUS passes STOPPING, the slides come to rest short of the target); a third
 * move cut by the e-stop input (no step from the next tick on, drives off at once, ESTOP); a
 * clear fault refused while the input is open and accepted once closed; homing again, and the
 * ESTOP command during a move (no step once it is read), cleared.  Throughout: no step
 * while the drives are off, slide speeds and accelerations measured on the plant within the
 * controller's limits (until the e-stop, which may stop dead), no frame lost. */
#include <stdint.h>
#include <string.h>

#include "fw/controller.h"
#include "fw/params.h"
#include "fw/proto.h"
#include "fw/runtime.h"
#include "kin_table.h"
#include "target_test.h"

#define NODE 1u
#define SEGMENT_HZ 1000u
#define STEP_HZ 200000u
#define TICKS (STEP_HZ / SEGMENT_HZ)
#define RING 64u

/* ---- CAN loopback ---------------------------------------------------------------------------- */

typedef struct {
    hal_can_frame f[RING];
    unsigned head, count, drops;
} ring;

static ring to_ctl, to_host;

static int ring_push(ring *r, const hal_can_frame *f)
{
    if (r->count == RING) {
        ++r->drops;
        return -1;
    }
    r->f[(r->head + r->count) % RING] = *f;
    ++r->count;
    return 0;
}

static int ring_pop(ring *r, hal_can_frame *f)
{
    if (r->count == 0)
        return 0;
    *f = r->f[r->head];
    r->head = (r->head + 1u) % RING;
    --r->count;
    return 1;
}

static int can_send(void *ctx, const hal_can_frame *f)
{
    (void)ctx;
    return ring_push(&to_host, f);
}

static int can_receive(void *ctx, hal_can_frame *f)
{
    (void)ctx;
    return ring_pop(&to_ctl, f);
}

static void can_state(void *ctx, hal_can_state *st)
{
    (void)ctx;
    memset(st, 0, sizeof *st);
}

/* ---- plant ----------------------------------------------------------------------------------- */

static struct {
    int32_t steps[6];  /* true position, steps from s = 0 */
    uint8_t dir;
    bool enabled;
    bool estop_open;
    int32_t home_sw_um[6];
    int64_t spm;
    unsigned long pulses, pulses_disabled;
    int32_t min_steps[6];
    uint64_t now_us;
} plant;

static void st_dir(void *ctx, uint8_t mask)
{
    (void)ctx;
    plant.dir = mask;
}

static void st_pulse(void *ctx, uint8_t mask)
{
    (void)ctx;
    for (int k = 0; k < 6; ++k) {
        if (!((mask >> k) & 1u))
            continue;
        plant.steps[k] += ((plant.dir >> k) & 1u) ? 1 : -1;
        if (plant.steps[k] < plant.min_steps[k])
            plant.min_steps[k] = plant.steps[k];
        ++plant.pulses;
        if (!plant.enabled)
            ++plant.pulses_disabled;
    }
}

static void st_enable(void *ctx, bool on)
{
    (void)ctx;
    plant.enabled = on;
}

static uint16_t in_limits(void *ctx)
{
    (void)ctx;
    uint16_t m = 0;
    for (int k = 0; k < 6; ++k)
        if ((int64_t)plant.steps[k] * 1000000 <= (int64_t)plant.home_sw_um[k] * plant.spm)
            m |= (uint16_t)(1u << k);
    return m;
}

static bool in_estop(void *ctx)
{
    (void)ctx;
    return plant.estop_open;
}

static uint64_t clk_now(void *ctx)
{
    (void)ctx;
    return plant.now_us;
}

static int sto_load(void *ctx, void *buf, size_t cap)
{
    (void)ctx;
    (void)buf;
    (void)cap;
    return 0; /* nothing stored: defaults */
}

static int sto_save(void *ctx, const void *buf, size_t len)
{
    (void)ctx;
    (void)buf;
    (void)len;
    return -1;
}

/* ---- host script's view ---------------------------------------------------------------------- */

#define LOG 48
static struct {
    int32_t state, fault, flags;
    unsigned statuses;
    int32_t log[LOG]; /* states in the order STATUS reported them (consecutive repeats merged) */
    unsigned nlog;
    int32_t slides_nm[6];
    int32_t fk[6]; /* um, urad */
    unsigned telemetry;
    unsigned acks, rejects;
    int32_t last_ack[5], last_reject[7];
    int32_t param_id, param_value;
    int32_t info[5]; /* the last INFO: major, minor, patch, step_hz, segment_hz */
    unsigned infos;
    unsigned undecodable;
    uint8_t seq;
} host;

static fw_controller_mem C_mem;
static fw_controller *C;

static void host_send(proto_msg m, const int32_t *v)
{
    hal_can_frame f;
    TT_CHECKF(proto_encode_values(m, NODE, v, &f) == 0, "%s not encodable\n", proto_table[m].name);
    TT_CHECK(ring_push(&to_ctl, &f) == 0);
}

static void host_cmd(proto_msg m)
{
    const int32_t v[1] = {host.seq++};
    host_send(m, v);
}

static void host_drain(void)
{
    hal_can_frame f;
    while (ring_pop(&to_host, &f)) {
        proto_message m;
        const proto_error e = proto_decode(&f, PROTO_TO_HOST, &m);
        if (e.reason != FW_REASON_NONE || m.node != NODE) {
            ++host.undecodable;
            continue;
        }
        switch (m.msg) {
        case PM_STATUS:
            host.state = m.v[0];
            host.fault = m.v[1];
            host.flags = m.v[2];
            ++host.statuses;
            if ((host.nlog == 0 || host.log[host.nlog - 1] != m.v[0]) && host.nlog < LOG)
                host.log[host.nlog++] = m.v[0];
            break;
        case PM_ACK:
            ++host.acks;
            memcpy(host.last_ack, m.v, sizeof host.last_ack);
            break;
        case PM_REJECT:
            ++host.rejects;
            memcpy(host.last_reject, m.v, sizeof host.last_reject);
            break;
        case PM_SLIDES_A:
        case PM_SLIDES_B:
        case PM_SLIDES_C:
            host.slides_nm[2 * (m.msg - PM_SLIDES_A)] = m.v[0];
            host.slides_nm[2 * (m.msg - PM_SLIDES_A) + 1] = m.v[1];
            ++host.telemetry;
            break;
        case PM_FK_A:
        case PM_FK_B:
        case PM_FK_C:
            host.fk[2 * (m.msg - PM_FK_A)] = m.v[0];
            host.fk[2 * (m.msg - PM_FK_A) + 1] = m.v[1];
            break;
        case PM_PARAM_VALUE:
            host.param_id = m.v[0];
            host.param_value = m.v[1];
            break;
        case PM_INFO:
            memcpy(host.info, m.v, sizeof host.info);
            ++host.infos;
            break;
        case PM_MOVE_INFO: /* after a move's ACK: how it starts, what set its pace */
        case PM_TRAJ_END:  /* how a trajectory ended */
            break;
        default:
            ++host.undecodable;
        }
    }
}

/* ---- motion monitor on the plant ------------------------------------------------------------- */

#define STRIDE 10u
static struct {
    bool on;
    int32_t hist[2 * STRIDE][6];
    unsigned n;
    double v_max, a_max; /* worst seen, m/s and m/s^2 */
    double v_lim, a_lim;
} mon;

static void monitor_start(void)
{
    for (unsigned j = 0; j < 2 * STRIDE; ++j)
        memcpy(mon.hist[j], plant.steps, sizeof mon.hist[0]);
    mon.n = 0;
    mon.on = true;
}

/* Sampled every millisecond, at the segment boundaries where the plant is on the rounded
 * setpoint: speed over 1 ms, acceleration as the second difference over 10 ms. */
static void monitor(void)
{
    if (!mon.on)
        return;
    const int32_t *prev = mon.hist[(mon.n + 2 * STRIDE - 1) % (2 * STRIDE)];
    const int32_t *old2 = mon.hist[mon.n % (2 * STRIDE)];
    const int32_t *old1 = mon.hist[(mon.n + STRIDE) % (2 * STRIDE)];
    const double T = (double)STRIDE / SEGMENT_HZ;
    for (int k = 0; k < 6; ++k) {
        const double v = (double)(plant.steps[k] - prev[k]) / (double)plant.spm * SEGMENT_HZ;
        const double a = (double)(plant.steps[k] - 2 * old1[k] + old2[k]) / (double)plant.spm / (T * T);
        if (v > mon.v_max || -v > mon.v_max)
            mon.v_max = v > 0 ? v : -v;
        if (a > mon.a_max || -a > mon.a_max)
            mon.a_max = a > 0 ? a : -a;
    }
    memcpy(mon.hist[mon.n % (2 * STRIDE)], plant.steps, sizeof mon.hist[0]);
    ++mon.n;
}

/* ---- run loop -------------------------------------------------------------------------------- */

static uint64_t ms_now;
static long estop_tick = -1;    /* step tick (of the next run) at which the e-stop input opens */
static unsigned long pulses_at_estop;
static bool estop_fired;

static void run(uint32_t ms)
{
    for (uint32_t i = 0; i < ms; ++i) {
        if (ms_now % 100 == 0) {
            const int32_t hb[1] = {(int32_t)(ms_now / 100 % 256)};
            host_send(PM_HOST_HEARTBEAT, hb);
        }
        fw_period_start(C, NULL, NULL);
        for (uint32_t t = 0; t < TICKS; ++t) {
            if (estop_tick >= 0 && (long)t == estop_tick) {
                /* the e-stop circuit opens: its interrupt preempts between two step ticks */
                plant.estop_open = true;
                fw_estop_isr(C);
                pulses_at_estop = plant.pulses;
                estop_fired = true;
                estop_tick = -1;
                mon.on = false; /* an e-stop may stop dead */
            }
            fw_step_tick(C);
        }
        plant.now_us += 1000000u / SEGMENT_HZ;
        ++ms_now;
        monitor();
        host_drain();
    }
}

/* Runs until STATUS reports `state` (at most ms); returns whether it did. */
static bool run_until(int32_t state, uint32_t ms)
{
    for (uint32_t i = 0; i < ms; i += 5) {
        run(5);
        if (host.statuses > 0 && host.state == state)
            return true;
    }
    return false;
}

static bool seen_in_log(unsigned from, int32_t state)
{
    for (unsigned i = from; i < host.nlog; ++i)
        if (host.log[i] == state)
            return true;
    return false;
}

/* Stages a pose (um, urad) in three parts and commits it as a move of `ms` milliseconds. */
static uint8_t move_to(const int32_t pose[6], int32_t ms)
{
    const uint8_t s = host.seq++;
    for (int part = 0; part < 3; ++part) {
        const int32_t v[3] = {s, pose[2 * part], pose[2 * part + 1]};
        host_send((proto_msg)(PM_POSE_A + part), v);
    }
    const int32_t m[3] = {s, 0, ms};
    host_send(PM_MOVE_COMMIT, m);
    return s;
}

static bool acked(proto_msg m, unsigned acks_before)
{
    return host.acks > acks_before && host.last_ack[0] == proto_table[m].function;
}

static bool rejected(proto_msg m, unsigned rejects_before, fw_reason reason)
{
    return host.rejects > rejects_before && host.last_reject[0] == proto_table[m].function &&
           host.last_reject[2] == (int32_t)reason;
}

static void param_set(fw_param_id id, int32_t value)
{
    const unsigned a = host.acks;
    const int32_t v[2] = {id, value};
    host_send(PM_PARAM_SET, v);
    run(2);
    TT_CHECKF(acked(PM_PARAM_SET, a), "PARAM_SET %s = %ld not acknowledged\n", fw_param_table[id].name, (long)value);
    TT_CHECK(host.param_id == (int32_t)id && host.param_value == value);
}

static long steps_of(double metres)
{
    const double x = metres * (double)plant.spm;
    return (long)(x >= 0 ? x + 0.5 : x - 0.5);
}

static long worst_off(int ref)
{
    long worst = 0;
    for (int k = 0; k < 6; ++k) {
        long d = (long)plant.steps[k] - steps_of(kin_refs[ref].q[k]);
        d = d < 0 ? -d : d;
        if (d > worst)
            worst = d;
    }
    return worst;
}

/* ---- the script ------------------------------------------------------------------------------ */

static uint32_t sim_ms_homing;

static void boot_and_params(void)
{
    memset(&plant, 0, sizeof plant);
    plant.spm = fw_param_table[FP_STEPS_PER_M].def;
    for (int k = 0; k < 6; ++k)
        plant.home_sw_um[k] = fw_param_table[FP_HOME_SW_1 + k].def;
    /* Power-up: slides 1-2 and 4 above their switches, slide 3 on its switch, 5 and 6 just above. */
    const double s0[6] = {0.215, 0.212, 0.199, 0.220, 0.2025, 0.2055};
    for (int k = 0; k < 6; ++k) {
        plant.steps[k] = (int32_t)steps_of(s0[k]);
        plant.min_steps[k] = plant.steps[k];
    }
    fw_hal hal;
    memset(&hal, 0, sizeof hal);
    hal.can = (hal_can){0, can_send, can_receive, can_state};
    hal.stepper = (hal_stepper){.ctx = 0, .set_dir = st_dir, .pulse = st_pulse, .enable = st_enable, .timing = 0};
    hal.inputs = (hal_inputs){0, in_limits, in_estop};
    hal.clock = (hal_clock){0, clk_now};
    hal.storage = (hal_storage){0, sto_load, sto_save};
    const fw_config cfg = {NODE, SEGMENT_HZ, STEP_HZ, NULL, NULL, NULL};
    C = fw_init(&C_mem, &hal, &cfg);
    TT_CHECK(C != NULL);
    host.seq = 1;
    run(5);
    TT_CHECK(host.statuses > 0 && host.state == FW_STATE_DISABLED && host.fault == FW_FAULT_NONE);
    TT_CHECK(!plant.enabled);
    /* INFO: the project's version (CMake's, given this test) and the rates configured above. */
    const unsigned acks = host.acks;
    const int32_t page[1] = {0};
    host_send(PM_INFO_GET, page);
    run(2);
    TT_CHECK(acked(PM_INFO_GET, acks) && host.infos == 1);
    TT_CHECK(host.info[0] == TSE_EXPECT_MAJOR && host.info[1] == TSE_EXPECT_MINOR && host.info[2] == TSE_EXPECT_PATCH);
    TT_CHECK(host.info[3] == (int32_t)STEP_HZ && host.info[4] == (int32_t)SEGMENT_HZ);
    /* STATUS every 10 ms, so that short states show; two switches elsewhere. */
    param_set(FP_STATUS_MS, 10);
    param_set(FP_HOME_SW_2, 205000);
    param_set(FP_HOME_SW_5, 196000);
    plant.home_sw_um[1] = 205000;
    plant.home_sw_um[4] = 196000;
    /* the new STATUS period starts once the one running (100 ms at boot) ends */
    run(100);
    const unsigned n = host.statuses;
    run(50);
    TT_CHECK(host.statuses >= n + 4 && host.statuses <= n + 6);
    /* The controller's slide limits, from the same defaults: 0.15 m/s capped at 90 % of what the
     * step generator holds (199 steps a segment after a 1-tick DIR set-up), 1 m/s^2. */
    mon.v_lim = 0.9 * 199.0 * SEGMENT_HZ / (double)plant.spm;
    if (fw_param_table[FP_SLIDE_VMAX].def * 1e-6 < mon.v_lim)
        mon.v_lim = fw_param_table[FP_SLIDE_VMAX].def * 1e-6;
    mon.a_lim = fw_param_table[FP_SLIDE_AMAX].def * 1e-6;
    TT_CHECK(plant.pulses == 0);
}

static void enable_and_home(void)
{
    unsigned a = host.acks;
    host_cmd(PM_ENABLE);
    run(3);
    TT_CHECK(acked(PM_ENABLE, a));
    TT_CHECK(plant.enabled);
    TT_CHECK(run_until(FW_STATE_IDLE, 50));
    monitor_start();
    a = host.acks;
    const unsigned log0 = host.nlog;
    const uint64_t t0 = ms_now;
    host_cmd(PM_HOME);
    TT_CHECK(run_until(FW_STATE_HOMING, 50));
    TT_CHECK(acked(PM_HOME, a));
    const bool done = run_until(FW_STATE_IDLE, 20000);
    sim_ms_homing = (uint32_t)(ms_now - t0);
    TT_CHECKF(done, "homing did not end (state %ld, fault %ld)\n", (long)host.state, (long)host.fault);
    TT_CHECK(seen_in_log(log0, FW_STATE_HOMING));
    TT_CHECK(host.fault == FW_FAULT_NONE);
    TT_CHECK((host.flags & 1) && (host.flags & 2)); /* homed, drives on */
    /* Every slide went down onto its switch, and the zero is true: the controller's count of each
     * slide is the plant's own position. */
    int32_t count[6];
    stepgen_positions(fw_stepgen_of(C), count);
    for (int k = 0; k < 6; ++k) {
        TT_CHECKF((int64_t)plant.min_steps[k] * 1000000 <= (int64_t)plant.home_sw_um[k] * plant.spm,
                  "slide %d never pressed its switch\n", k + 1);
        TT_CHECKF(count[k] == plant.steps[k], "slide %d: controller counts %ld, plant at %ld\n", k + 1, (long)count[k],
                  (long)plant.steps[k]);
    }
    /* At the symmetric home configuration: six equal slides, reported by telemetry. */
    run(60);
    for (int k = 1; k < 6; ++k)
        TT_CHECK(plant.steps[k] == plant.steps[0]);
    for (int k = 0; k < 6; ++k) {
        const long plant_nm = (long)((double)plant.steps[k] * 1e9 / (double)plant.spm);
        const long d = (long)host.slides_nm[k] - plant_nm;
        TT_CHECKF(d <= 100 && d >= -100, "telemetry slide %d: %ld nm, plant %ld nm\n", k + 1, (long)host.slides_nm[k],
                  plant_nm);
    }
    sh_printf("  homed in %lu ms of simulated time; home slides at %ld steps\n", (unsigned long)sim_ms_homing,
              (long)plant.steps[0]);
}

static void move_and_land(void)
{
    const unsigned a = host.acks, log0 = host.nlog;
    const uint8_t s = move_to(kin_refs[REF_CTL_A].pose_u, 700);
    run(3);
    TT_CHECK(acked(PM_MOVE_COMMIT, a) && host.last_ack[1] == s);
    const int32_t planned_ms = host.last_ack[4];
    TT_CHECK(planned_ms >= 700);
    TT_CHECK(run_until(FW_STATE_MOVING, 20));
    TT_CHECK(run_until(FW_STATE_IDLE, (uint32_t)planned_ms + 200));
    TT_CHECK(seen_in_log(log0, FW_STATE_MOVING));
    TT_CHECK(host.fault == FW_FAULT_NONE);
    /* The plant's slides on the double IK of the pose: the float IK is within 2 um of it
     * (kinematics.md), rounding to steps adds half a step (0.39 um): 3 steps (2.3 um). */
    const long off = worst_off(REF_CTL_A);
    TT_CHECKF(off <= 3, "a slide is %ld steps off the double solution\n", off);
    /* Telemetry: the FK pose of the slides, within a few micrometres of the pose. */
    run(60);
    long fk_off = 0;
    for (int k = 0; k < 6; ++k) {
        long d = (long)host.fk[k] - kin_refs[REF_CTL_A].pose_u[k];
        d = d < 0 ? -d : d;
        if (d > fk_off)
            fk_off = d;
    }
    TT_CHECKF(fk_off <= 20, "telemetry FK %ld um/urad off the pose\n", fk_off);
    sh_printf("  move 1: planned %ld ms; slides within %ld step(s) of the double IK; FK telemetry within %ld "
              "um/urad\n",
              (long)planned_ms, off, fk_off);
}

static void stop_half_way(void)
{
    const unsigned a = host.acks, log0 = host.nlog;
    int32_t start[6];
    memcpy(start, plant.steps, sizeof start);
    move_to(kin_refs[REF_CTL_B].pose_u, 1200);
    run(3);
    TT_CHECK(acked(PM_MOVE_COMMIT, a));
    const int32_t planned_ms = host.last_ack[4];
    run(500); /* in the cruise */
    TT_CHECK(host.state == FW_STATE_MOVING);
    const unsigned a2 = host.acks;
    host_cmd(PM_STOP);
    run(2);
    TT_CHECK(acked(PM_STOP, a2));
    TT_CHECK(run_until(FW_STATE_IDLE, 1000));
    TT_CHECK(seen_in_log(log0, FW_STATE_STOPPING));
    TT_CHECK(host.fault == FW_FAULT_NONE);
    /* At rest: no pulse over the next 50 ms; short of the target; moved towards it. */
    const unsigned long p = plant.pulses;
    run(50);
    TT_CHECK(plant.pulses == p);
    const long off = worst_off(REF_CTL_B);
    TT_CHECKF(off > 100, "the stop ended on the target (%ld steps)\n", off);
    long moved = 0;
    for (int k = 0; k < 6; ++k) {
        const long d = (long)plant.steps[k] - start[k];
        moved += d < 0 ? -d : d;
    }
    TT_CHECK(moved > 100);
    unsigned i = log0;
    while (i < host.nlog && host.log[i] != FW_STATE_STOPPING)
        ++i;
    sh_printf("  move 2: planned %ld ms, stopped at 500 ms: STATUS went", (long)planned_ms);
    for (unsigned j = log0; j < host.nlog; ++j)
        sh_printf(" %s", proto_enum_name(proto_state_names, host.log[j]));
    sh_printf("; at rest %ld steps from the target\n", off);
}

static void estop_mid_move(void)
{
    const unsigned a = host.acks;
    move_to(kin_refs[REF_CTL_A].pose_u, 1000);
    run(3);
    TT_CHECK(acked(PM_MOVE_COMMIT, a));
    run(300);
    TT_CHECK(host.state == FW_STATE_MOVING);
    const unsigned long before = plant.pulses;
    run(10);
    TT_CHECK(plant.pulses > before); /* stepping when the e-stop comes */
    estop_tick = 87;                 /* in the middle of a segment */
    run(1);
    TT_CHECK(estop_fired);
    TT_CHECK(!plant.enabled);        /* switched off in the interrupt */
    run(300);
    TT_CHECKF(plant.pulses == pulses_at_estop, "%lu steps after the e-stop\n", plant.pulses - pulses_at_estop);
    TT_CHECK(host.state == FW_STATE_ESTOP && host.fault == FW_FAULT_ESTOP);
    TT_CHECK((host.flags & 4) && !(host.flags & 1) && !(host.flags & 2)); /* input open, zero dropped, drives off */
    TT_CHECK(!plant.enabled);
    sh_printf("  e-stop at step tick 87 of a segment: %lu steps after it\n", plant.pulses - pulses_at_estop);
}

static void clear_fault(void)
{
    unsigned r = host.rejects;
    host_cmd(PM_CLEAR_FAULT);
    run(3);
    TT_CHECK(rejected(PM_CLEAR_FAULT, r, FW_REASON_STATE)); /* the input is still open */
    TT_CHECK(host.state == FW_STATE_ESTOP);
    plant.estop_open = false;
    run(20);
    const unsigned a = host.acks;
    host_cmd(PM_CLEAR_FAULT);
    run(15);
    TT_CHECK(acked(PM_CLEAR_FAULT, a));
    TT_CHECK(host.state == FW_STATE_DISABLED && host.fault == FW_FAULT_NONE);
    TT_CHECK(!(host.flags & 1) && !(host.flags & 2) && !(host.flags & 4));
    /* Enabled again, a move is refused until homing: the zero went with the e-stop. */
    host_cmd(PM_ENABLE);
    TT_CHECK(run_until(FW_STATE_IDLE, 50));
    r = host.rejects;
    move_to(kin_refs[REF_CTL_B].pose_u, 1000);
    run(3);
    TT_CHECK(rejected(PM_MOVE_COMMIT, r, FW_REASON_NOT_HOMED));
    TT_CHECK(plant.pulses == pulses_at_estop);
}

/* The ESTOP command mid-move: no step once the poll that reads it has run. */
static void estop_command(void)
{
    monitor_start();
    TT_CHECK(host.state == FW_STATE_IDLE);
    unsigned a = host.acks;
    host_cmd(PM_HOME);
    TT_CHECK(run_until(FW_STATE_HOMING, 50));
    TT_CHECK(run_until(FW_STATE_IDLE, 20000));
    TT_CHECK(acked(PM_HOME, a) || host.acks > a);
    TT_CHECK(host.flags & 1);
    a = host.acks;
    move_to(kin_refs[REF_CTL_B].pose_u, 1000);
    run(400);
    TT_CHECK(acked(PM_MOVE_COMMIT, a));
    TT_CHECK(host.state == FW_STATE_MOVING);
    const unsigned long before = plant.pulses;
    run(5);
    TT_CHECK(plant.pulses > before);
    a = host.acks;
    host_cmd(PM_ESTOP); /* read by the next poll, before the next step tick */
    const unsigned long at = plant.pulses;
    mon.on = false;
    run(200);
    TT_CHECKF(plant.pulses == at, "%lu steps after the ESTOP command\n", plant.pulses - at);
    TT_CHECK(acked(PM_ESTOP, a) || host.acks > a);
    TT_CHECK(host.state == FW_STATE_ESTOP && host.fault == FW_FAULT_ESTOP && !plant.enabled);
    /* the input is closed: cleared at once, back to DISABLED */
    a = host.acks;
    host_cmd(PM_CLEAR_FAULT);
    run(15);
    TT_CHECK(acked(PM_CLEAR_FAULT, a));
    TT_CHECK(host.state == FW_STATE_DISABLED && host.fault == FW_FAULT_NONE);
    sh_printf("  ESTOP command during a move: %lu steps after it\n", plant.pulses - at);
}

static void whole_run(void)
{
    TT_CHECK(plant.pulses_disabled == 0);
    TT_CHECK(to_host.drops == 0 && to_ctl.drops == 0);
    TT_CHECK(host.undecodable == 0);
    TT_CHECKF(mon.v_max <= mon.v_lim + 1.0 / (double)plant.spm * SEGMENT_HZ,
              "slide speed %ld um/s, limit %ld um/s\n", (long)(mon.v_max * 1e6), (long)(mon.v_lim * 1e6));
    /* the plant sits on the rounded setpoints: +-0.5 step each, 2 steps over the difference */
    TT_CHECKF(mon.a_max <= mon.a_lim + 2.0 / (double)plant.spm / 1e-4,
              "slide acceleration %ld mm/s^2, limit %ld mm/s^2\n", (long)(mon.a_max * 1e3), (long)(mon.a_lim * 1e3));
    sh_printf("  %lu ms simulated, %lu steps; worst slide speed %ld um/s (limit %ld), acceleration %ld mm/s^2 "
              "(limit %ld); %u STATUS frames, %u ACK, %u REJECT\n",
              (unsigned long)ms_now, plant.pulses, (long)(mon.v_max * 1e6), (long)(mon.v_lim * 1e6),
              (long)(mon.a_max * 1e3), (long)(mon.a_lim * 1e3), host.statuses, host.acks, host.rejects);
}

int main(void)
{
    tt_begin("controller");
    tt_case("boot, parameters over CAN", boot_and_params);
    tt_case("enable and home on the scripted switches", enable_and_home);
    tt_case("move: ACK, MOVING then IDLE, slides on the double IK", move_and_land);
    tt_case("STOP during a move: STOPPING, at rest short of the target", stop_half_way);
    tt_case("e-stop input during a move: no step after it", estop_mid_move);
    tt_case("clear fault: refused while open, then DISABLED and not homed", clear_fault);
    tt_case("homed again, ESTOP command during a move: no step after it, cleared", estop_command);
    tt_case("whole run: no step disabled, limits kept, no frame lost", whole_run);
    tt_finish();
}
