/* Instruction counts on the emulated Cortex-M4F (QEMU netduinoplus2 with -icount shift=0): TIM2
 * at prescaler 0 then gains exactly one count per guest instruction, so reading its counter
 * around a call counts the call's instructions (minus the cost of the read itself, measured and
 * subtracted).  No interrupt is enabled.  Prints one line per figure, `name,instructions`,
 * the median over many calls; a benchmark, never a test.  Release flags, float kinematics:
 * the code that runs on the board. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fw/controller.h"
#include "fw/inspect.h"
#include "fw/move.h"
#include "fw/proto.h"
#include "fw/runtime.h"
#include "fw/stepgen.h"
#include "fw/testing.h"
#include "hal_stm32f4/regs_rcc.h"
#include "hal_stm32f4/regs_tim.h"
#include "hal_stm32f4/semihost.h"
#include "tse/fk.h"
#include "tse/ik.h"

#define MAX_SAMPLES 2048

static uint32_t samples[MAX_SAMPLES];
static uint32_t overhead;

static inline uint32_t count(void)
{
    return TSE_TIM2->CNT;
}

static void counter_start(void)
{
    TSE_RCC->APB1ENR |= RCC_APB1ENR_TIM2;
    TSE_TIM2->CR1 = 0;
    TSE_TIM2->PSC = 0;
    TSE_TIM2->ARR = 0xFFFFFFFFu;
    TSE_TIM2->EGR = TIM_EGR_UG;
    TSE_TIM2->CR1 = TIM_CR1_CEN;
    /* Two reads back to back: what a measurement of nothing reads. */
    uint32_t lo = UINT32_MAX;
    for (int i = 0; i < 16; ++i) {
        const uint32_t a = count();
        const uint32_t b = count();
        if (b - a < lo)
            lo = b - a;
    }
    overhead = lo;
}

static int cmp_u32(const void *a, const void *b)
{
    const uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return (x > y) - (x < y);
}

static void report(const char *name, uint32_t *v, unsigned n, int use_max)
{
    qsort(v, n, sizeof *v, cmp_u32);
    sh_printf("%s,%lu\n", name, (unsigned long)(use_max ? v[n - 1] : v[n / 2]));
}

#define MEASURE(dst, call)                                                                       \
    do {                                                                                         \
        const uint32_t t0_ = count();                                                            \
        call;                                                                                    \
        const uint32_t t1_ = count();                                                            \
        (dst) = t1_ - t0_ - overhead;                                                            \
    } while (0)

static tse_geometry geom;

/* A smooth path through the workspace (the host benchmark's Lissajous figure). */
static void path_pose(unsigned i, unsigned n, tse_real p[6])
{
    const tse_real t = TSE_R(6.283185307) * (tse_real)i / (tse_real)n;
    p[0] = TSE_R(0.08) * tse_sin(t);
    p[1] = TSE_R(0.06) * tse_sin(TSE_R(2.0) * t);
    p[2] = TSE_R(1.05) + TSE_R(0.15) * tse_sin(TSE_R(3.0) * t);
    p[3] = TSE_R(0.05) * tse_sin(t + TSE_R(0.3));
    p[4] = TSE_R(0.05) * tse_cos(TSE_R(2.0) * t);
    p[5] = TSE_R(0.1) * tse_sin(t);
}

static void bench_kinematics(void)
{
    enum { N = 1000 };
    tse_ik_result r;
    tse_real p[6], q[6];
    path_pose(0, N, p);
    tse_ik(&geom, p, NULL, &r);
    memcpy(q, r.q, sizeof q);
    unsigned warm = 0, cold = 0, fk = 0;
    tse_real prev[6];
    memcpy(prev, p, sizeof prev);
    for (unsigned i = 1; i <= N && warm < MAX_SAMPLES; ++i) {
        path_pose(i, N, p);
        uint32_t n;
        MEASURE(n, tse_ik(&geom, p, q, &r));
        if (r.status == TSE_OK)
            samples[warm++] = n;
        memcpy(q, r.q, sizeof q);
    }
    report("ik_float_warm", samples, warm, 0);
    for (unsigned i = 1; i <= N; i += 2) {
        path_pose(i, N, p);
        uint32_t n;
        MEASURE(n, tse_ik(&geom, p, NULL, &r));
        if (r.status == TSE_OK)
            samples[cold++] = n;
    }
    report("ik_float_cold", samples, cold, 0);
    for (unsigned i = 1; i <= N; i += 2) {
        path_pose(i, N, p);
        tse_ik(&geom, p, NULL, &r);
        if (r.status != TSE_OK)
            continue;
        tse_fk_result f;
        uint32_t n;
        MEASURE(n, tse_fk(&geom, r.q, prev, &f));
        if (f.status == TSE_OK)
            samples[fk++] = n;
        memcpy(prev, p, sizeof prev);
    }
    report("fk_float", samples, fk, 0);
}

static void bench_stepgen(void)
{
    /* 200 kHz step interrupts over 1 kHz segments; every axis moves 190 steps a segment
     * (190 kHz, the prototype's top speed), alternating directions between axes. */
    static stepgen sg;
    const stepgen_config cfg = {200, 1, 1};
    const int32_t zero[6] = {0};
    stepgen_init(&sg, &cfg, zero);
    int32_t target[6] = {0};
    unsigned n_all = 0, n_first = 0;
    static uint32_t first[64];
    for (int s = 0; s < 40; ++s) {
        for (int k = 0; k < 6; ++k)
            target[k] += k % 2 ? -190 : 190;
        stepgen_push(&sg, target);
        for (int t = 0; t < 200; ++t) {
            stepgen_output o;
            uint32_t n;
            MEASURE(n, o = stepgen_tick(&sg));
            if (t == 0)
                first[n_first++] = n;
            else if (o.step_mask == 0x3Fu && n_all < MAX_SAMPLES)
                samples[n_all++] = n;
        }
    }
    report("step_tick_6axes", samples, n_all, 0);
    report("step_tick_6axes_max", first, n_first, 1);
}

/* The controller on an in-RAM HAL: enough to run its control tick while moving.  Frames come
 * through a small ring the benchmark fills and the controller's poll empties. */
static uint64_t fake_now;
static hal_can_frame rx[8];
static unsigned rx_head, rx_count;
static int can_send(void *c, const hal_can_frame *f) { (void)c; (void)f; return 0; }
static int can_receive(void *c, hal_can_frame *f)
{
    (void)c;
    if (rx_count == 0)
        return 0;
    *f = rx[rx_head];
    rx_head = (rx_head + 1u) % 8u;
    --rx_count;
    return 1;
}
static void can_state(void *c, hal_can_state *s) { (void)c; memset(s, 0, sizeof *s); }
static void st_dir(void *c, uint8_t m) { (void)c; (void)m; }
static void st_pulse(void *c, uint8_t m) { (void)c; (void)m; }
static void st_enable(void *c, bool on) { (void)c; (void)on; }
static uint16_t in_limits(void *c) { (void)c; return 0; }
static bool in_estop(void *c) { (void)c; return false; }
static uint64_t clk_now(void *c) { (void)c; return fake_now; }
static int st_load(void *c, void *b, size_t n) { (void)c; (void)b; (void)n; return 0; }
static int st_save(void *c, const void *b, size_t n) { (void)c; (void)b; (void)n; return -1; }

static fw_controller_mem ctl_mem;
static fw_controller *ctl;

/* Queues a frame for the controller's next poll. */
static void frame(proto_msg msg, const int32_t *v)
{
    proto_message m;
    memset(&m, 0, sizeof m);
    m.msg = msg;
    m.node = 1;
    for (int i = 0; i < proto_table[msg].nfields; ++i)
        m.v[i] = v[i];
    hal_can_frame f;
    proto_encode(&m, &f);
    rx[(rx_head + rx_count) % 8u] = f;
    ++rx_count;
}

static void stage(uint8_t seq, const tse_real pose[6])
{
    for (int part = 0; part < 3; ++part) {
        const int32_t v[3] = {seq, (int32_t)(pose[2 * part] * TSE_R(1e6)), (int32_t)(pose[2 * part + 1] * TSE_R(1e6))};
        frame((proto_msg)(PM_POSE_A + part), v);
    }
    fw_poll(ctl);
}

/* A control period with the host alive: the control tick (measured into *c if c), the step ticks. */
static void period(uint32_t *c)
{
    fake_now += 1000;
    frame(PM_HOST_HEARTBEAT, (const int32_t[]){0});
    fw_poll(ctl);
    if (c)
        MEASURE(*c, fw_control_tick(ctl));
    else
        fw_control_tick(ctl);
    for (int t = 0; t < 200; ++t)
        fw_step_tick(ctl);
}

static uint32_t segments_of_running(void)
{
    static fw_inspection in;
    fw_inspect(ctl, &in);
    return in.has_next ? in.next.segments : in.move.segments;
}

static void bench_controller(void)
{
    fw_hal hal;
    memset(&hal, 0, sizeof hal);
    hal.can = (hal_can){0, can_send, can_receive, can_state};
    hal.stepper = (hal_stepper){.set_dir = st_dir, .pulse = st_pulse, .enable = st_enable};
    hal.inputs = (hal_inputs){0, in_limits, in_estop};
    hal.clock = (hal_clock){0, clk_now};
    hal.storage = (hal_storage){0, st_load, st_save};
    const fw_config cfg = {1, 1000, 200000, NULL, NULL};
    ctl = fw_init(&ctl_mem, &hal, &cfg);
    /* Homed at the home pose without running the homing sequence (a benchmark shortcut: it
     * needs switches), then enabled. */
    if (!ctl || fw_testing_homed_at_home(ctl) != 0) {
        sh_puts("bench: controller did not start\n");
        return;
    }
    frame(PM_ENABLE, (const int32_t[]){0});
    fw_poll(ctl);
    fw_control_tick(ctl);

    /* Commit-to-first-setpoint: the commit's validation (the poll that takes it), for a 1 s and a
     * 5 s move from rest, then a 5 s move blended into the running 5 s one. */
    static const struct {
        const char *name;
        tse_real to[6];
        int32_t ms;
    } moves[3] = {{"commit_1s", {0.05f, -0.03f, 1.10f, 0.03f, -0.02f, 0.10f}, 1000},
                  {"commit_5s", {-0.10f, 0.08f, 1.30f, -0.05f, 0.04f, -0.20f}, 5000},
                  {"validate_blend", {0.08f, -0.06f, 1.00f, 0.04f, -0.03f, 0.15f}, 5000}};
    uint8_t seq = 1;
    for (int m = 0; m < 3; ++m) {
        if (m == 2) /* a second into the first 5 s move */
            for (int i = 0; i < 1000; ++i)
                period(NULL);
        stage(seq, moves[m].to);
        uint32_t n;
        frame(PM_MOVE_COMMIT, ((const int32_t[]){seq, 0, moves[m].ms}));
        MEASURE(n, fw_poll(ctl));
        ++seq;
        const uint32_t segs = segments_of_running();
        sh_printf("%s,%lu\n", moves[m].name, (unsigned long)n);
        if (m < 2)
            sh_printf("validate_segment_%s,%lu\n", moves[m].name + 7, (unsigned long)(segs ? n / segs : 0));
        if (m == 1)
            continue; /* the blend joins it */
        /* Run the move: control ticks measured, step ticks between them not. */
        unsigned k = 0;
        while (fw_state_of(ctl) == FW_STATE_MOVING) {
            uint32_t c;
            period(&c);
            if (k < MAX_SAMPLES && fw_state_of(ctl) == FW_STATE_MOVING)
                samples[k++] = c;
        }
        if (m == 0)
            report("control_segment", samples, k, 0);
    }
}

int main(void)
{
    counter_start();
    sh_printf("# instruction counts on the emulated Cortex-M4F (QEMU -icount shift=0), medians; read overhead %lu\n",
              (unsigned long)overhead);
    fw_param_set ps;
    fw_params_default(&ps);
    tse_params kp;
    fw_params_kinematics(&ps, &kp);
    tse_geometry_init(&geom, &kp);
    bench_kinematics();
    bench_stepgen();
    bench_controller();
    sh_exit(0);
}
