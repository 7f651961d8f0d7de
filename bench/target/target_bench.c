/* Instruction counts on the emulated Cortex-M4F (QEMU netduinoplus2 with -icount shift=0): TIM2
 * at prescaler 0 then gains exactly one count per guest instruction, so reading its counter
 * around a call counts the call's instructions (minus the cost of the read itself, measured and
 * subtracted).  No interrupt is enabled.  Prints one line per figure, `name,instructions`,
 * the median over many calls; a benchmark, never a test.  Release flags, float kinematics:
 * the code that runs on the board. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "bench_rig.h"
#include "frame_cases.h"
#include "fw/inspect.h"
#include "fw/move.h"
#include "fw/runtime.h"
#include "fw/stepgen.h"
#include "hal_stm32f4/board_io.h"
#include "hal_stm32f4/regs_tim.h"
#include "hal_stm32f4/semihost.h"
#include "tse/enclose.h"
#include "tse/fk.h"
#include "tse/ik.h"

#define MAX_SAMPLES 2048

static uint32_t samples[MAX_SAMPLES];
static uint32_t overhead;
static uint32_t blend_hold; /* the blend's longest stretch away from the bus (bench_frames) */

static inline uint32_t count(void)
{
    return bench_count();
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
    /* A piece of the path around each pose, as validation encloses them: the position's and the
     * orientation's change over a neighbourhood of +-1 path step (the orientation's rates taken
     * as the angles' differences: the cost, not the proof, is what is measured here). */
    unsigned enc = 0;
    for (unsigned i = 1; i <= N; i += 2) {
        tse_real a[6], b[6];
        path_pose(i, N, p);
        path_pose(i - 1u, N, a);
        path_pose(i + 1u, N, b);
        tse_ik(&geom, p, NULL, &r);
        if (r.status != TSE_OK)
            continue;
        tse_piece pc = {{0}, {0}, TSE_R(0.5), TSE_R(1e-7)};
        for (int k = 0; k < 3; ++k) {
            pc.lin[k] = (b[k] - a[k]) * TSE_R(0.5);
            pc.omega[k] = (b[3 + k] - a[3 + k]) * TSE_R(0.5);
        }
        tse_enclosure e;
        uint32_t n;
        MEASURE(n, tse_ik_enclose(&geom, &pc, p, &r, &e));
        if (e.proven)
            samples[enc++] = n;
    }
    report("enclose_float", samples, enc, 0);
}

/* One step interrupt as fw_step_tick makes it: the step generator, then, with outputs (h not
 * NULL), DIR where it changed and the STEP pulse, as the board's stepout.c writes them. */
static stepgen_output step_once(stepgen *sg, const hal_stepper *h)
{
    const stepgen_output o = stepgen_tick(sg);
    if (h) {
        if (o.dir_changed)
            h->set_dir(h->ctx, o.forward_mask);
        if (o.step_mask)
            h->pulse(h->ctx, o.step_mask);
    }
    return o;
}

static void step_ticks(const hal_stepper *h, const char *name, const char *name_max)
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
            MEASURE(n, o = step_once(&sg, h));
            if (t == 0)
                first[n_first++] = n;
            else if (o.step_mask == 0x3Fu && n_all < MAX_SAMPLES)
                samples[n_all++] = n;
        }
    }
    report(name, samples, n_all, 0);
    report(name_max, first, n_first, 1);
}

/* The board's outputs on description d, TIM4's interrupt (the pulse's end) off: its instructions
 * would land in whichever sample it interrupts. */
static hal_stepper outputs_on(const board_desc *d)
{
    const hal_stepper h = board_stepper_hal_for(d, 84000000u, -1);
    TSE_TIM4->DIER = 0;
    return h;
}

static void bench_stepgen(void)
{
    step_ticks(NULL, "step_tick_6axes", "step_tick_6axes_max");
    /* gen_f405: STEP1..6 on PC0..PC5, DIR on PC6..PC11: one BSRR write each. */
    const hal_stepper fast = outputs_on(&tse_board_desc);
    step_ticks(&fast, "step_tick_6axes_fast", "step_tick_6axes_fast_max");
    /* The same with monster8's STEP and DIR pins (hal/stm32f4/boards/monster8.h), on four
     * ports: a write per slide. */
    static board_desc scattered;
    scattered = tse_board_desc;
    static const uint8_t step[6] = {BOARD_PIN(C, 14), BOARD_PIN(E, 5), BOARD_PIN(E, 1),
                                    BOARD_PIN(B, 5),  BOARD_PIN(D, 6), BOARD_PIN(D, 2)};
    static const uint8_t dir[6] = {BOARD_PIN(C, 13), BOARD_PIN(E, 4), BOARD_PIN(E, 0),
                                   BOARD_PIN(B, 4),  BOARD_PIN(D, 5), BOARD_PIN(D, 1)};
    memcpy(scattered.step, step, sizeof step);
    memcpy(scattered.dir, dir, sizeof dir);
    const hal_stepper per_slide = outputs_on(&scattered);
    step_ticks(&per_slide, "step_tick_6axes_per_slide", "step_tick_6axes_per_slide_max");
    outputs_on(&tse_board_desc);
}

static uint32_t segments_of_running(void)
{
    static fw_inspection in;
    fw_inspect(bench_ctl, &in);
    return in.has_next ? in.next.segments : in.move.segments;
}

static void bench_controller(void)
{
    if (bench_rig_start() != 0) {
        sh_puts("bench: controller did not start\n");
        return;
    }
    fw_controller *const ctl = bench_ctl;

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
                bench_period(NULL);
        bench_stage(seq, moves[m].to);
        uint32_t n;
        bench_queue(PM_MOVE_COMMIT, ((const int32_t[]){seq, 0, moves[m].ms}));
        bench_hold_begin();
        MEASURE(n, fw_poll(ctl));
        const uint32_t hold = bench_hold_end();
        if (m == 2)
            blend_hold = hold;
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
            bench_period(&c);
            if (k < MAX_SAMPLES && fw_state_of(ctl) == FW_STATE_MOVING)
                samples[k++] = c;
        }
        if (m == 0)
            report("control_segment", samples, k, 0);
    }
}

/* Over the adversarial commits of frame_cases.c (docs/validation.md, "What one frame costs"), each
 * from rest, and the blend above: the longest the thread went without reading the bus while it
 * handled one frame (frame_worst: how long one frame holds the board), and the costliest commit's
 * handling whole, to its answer (commit_worst). */
static void bench_frames(void)
{
    if (bench_rig_start() != 0) {
        sh_puts("bench: controller did not start\n");
        return;
    }
    uint32_t worst = 0, hold_worst = blend_hold;
    unsigned at = 0, hold_at = 0; /* case + 1; 0: the blend */
    char answer = 0;
    int reason = 0;
    for (unsigned i = 0; i < bench_frame_case_count; ++i) {
        char a;
        int r;
        uint32_t hold;
        const uint32_t n = bench_commit_cost(&bench_frame_cases[i], &a, &r, &hold);
        if (n >= worst) {
            worst = n;
            at = i;
            answer = a;
            reason = r;
        }
        if (hold > hold_worst) {
            hold_worst = hold;
            hold_at = i + 1u;
        }
    }
    if (hold_at == 0)
        sh_printf("frame_worst,%lu\n# frame_worst: the blend (validate_blend), over it and %u adversarial commits\n",
                  (unsigned long)hold_worst, bench_frame_case_count);
    else
        sh_printf("frame_worst,%lu\n# frame_worst: case %u of %u\n", (unsigned long)hold_worst, hold_at,
                  bench_frame_case_count);
    if (worst == UINT32_MAX)
        sh_printf("commit_worst,4294967296\n# commit_worst: at least that (case %u of %u wrapped the counter)\n",
                  at + 1, bench_frame_case_count);
    else
        sh_printf("commit_worst,%lu\n# commit_worst: case %u of %u (%s)\n", (unsigned long)worst, at + 1,
                  bench_frame_case_count, answer == 'a' ? "accepted" : answer == 'r' ? proto_enum_name(proto_reason_names, reason) : "no answer");
}

int main(void)
{
    overhead = bench_counter_start();
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
    bench_frames();
    sh_exit(0);
}
