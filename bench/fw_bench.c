/* Firmware timing on the host (the board issue adds instruction counts on the target):
 * - one control segment as the controller runs it: the pose on the path, the inverse kinematics
 *   warm-started from the previous segment, the setpoint in steps;
 * - planning: validating a whole move, per segment of it;
 * - the step interrupt: one tick of the six-axis step generator at full and at typical rates.
 * Medians over repeated batches; printed, never asserted. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "bench_clock.h"
#include "fw/move.h"
#include "fw/params.h"
#include "fw/stepgen.h"

int main(void)
{
    enum { REPEATS = 21 };
    fw_param_set ps;
    fw_params_default(&ps);
    tse_params kp;
    fw_params_kinematics(&ps, &kp);
    tse_geometry g;
    tse_geometry_init(&g, &kp);
    const fw_limits lim = {0.18, 0.95, 0.3, 1.0, 10.0, 0.5, 2.0, 1000.0, FW_LIMIT_SLIDE_VMAX};
    const tse_real from[6] = {0, 0, 1.0, 0, 0, 0}, to[6] = {0.12, -0.08, 1.3, 0.05, -0.05, 0.2};
    tse_ik_result r;
    tse_ik(&g, from, NULL, &r);
    tse_real q0[6];
    for (int k = 0; k < 6; ++k)
        q0[k] = r.q[k];

    fw_move mv;
    fw_plan_result res;
    double plan[REPEATS], seg[REPEATS];
    volatile double sink = 0;
    for (int rep = 0; rep < REPEATS; ++rep) {
        double t0 = bench_now_ns();
        if (fw_move_plan(&mv, &g, &lim, from, to, FW_MOVE_DURATION, 1.0, q0, &res) != 0)
            return 1;
        plan[rep] = (bench_now_ns() - t0) / mv.segments;

        tse_real q[6];
        for (int k = 0; k < 6; ++k)
            q[k] = q0[k];
        t0 = bench_now_ns();
        for (uint32_t s = 1; s <= mv.segments; ++s) {
            tse_real pose[6];
            fw_move_pose(&mv, fw_move_segment_time(&mv, &lim, s), pose);
            tse_ik(&g, pose, q, &r);
            int32_t steps[6];
            for (int k = 0; k < 6; ++k) {
                q[k] = r.q[k];
                steps[k] = (int32_t)(q[k] * (tse_real)ps.v[FP_STEPS_PER_M] + TSE_R(0.5));
            }
            sink += steps[0];
        }
        seg[rep] = (bench_now_ns() - t0) / mv.segments;
    }
    printf("move of %u segments (%.3f s after stretching x%.2f)\n", mv.segments, (double)mv.prof.T, (double)mv.stretch);
    printf("control segment (pose + warm IK + steps): median %.1f ns\n", bench_median(seg, REPEATS));
    printf("planning (whole-path validation), per segment: median %.1f ns\n", bench_median(plan, REPEATS));
    printf("bench,segment_ns,%.1f\nbench,plan_per_segment_ns,%.1f\n", bench_median(seg, REPEATS), bench_median(plan, REPEATS));

    /* The step interrupt: 200 kHz over 1 kHz segments; every axis at its capacity, or at a
     * typical 20 kHz. */
    const stepgen_config cfg = {200, 1, 2};
    for (int full = 1; full >= 0; --full) {
        double tick[REPEATS];
        for (int rep = 0; rep < REPEATS; ++rep) {
            stepgen sg;
            const int32_t zero[6] = {0};
            stepgen_init(&sg, &cfg, zero);
            int32_t target[6] = {0};
            const int32_t per = full ? 99 : 20;
            long ticks = 0;
            const double t0 = bench_now_ns();
            for (int s = 0; s < 2000; ++s) {
                for (int k = 0; k < 6; ++k)
                    target[k] += (k % 2 ? -per : per);
                stepgen_push(&sg, target);
                for (int t = 0; t < 200; ++t, ++ticks)
                    sink += stepgen_tick(&sg).step_mask;
            }
            tick[rep] = (bench_now_ns() - t0) / (double)ticks;
        }
        printf("step interrupt, 6 axes at %s: median %.2f ns per tick\n", full ? "99 kHz each" : "20 kHz each",
               bench_median(tick, REPEATS));
        printf("bench,step_tick_%s_ns,%.2f\n", full ? "full" : "typical", bench_median(tick, REPEATS));
    }
    (void)sink;
    return 0;
}
