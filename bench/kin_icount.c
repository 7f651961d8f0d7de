/* kin-icount: the operations whose instructions scripts/kin_icount.sh counts under callgrind, one
 * noinline function each (measure_...), so that `valgrind --tool=callgrind
 * --toggle-collect=measure_X kin-icount measure_X` counts exactly X's inclusive instructions.
 *
 * Inputs: the 2000-pose path of `tse-kin bench` (pose k at t = 0.002 k) and the prototype design
 * (tse_params_default), in both precisions; and for validate_segment, the firmware's move planning
 * (fw_move_plan) of a 5 s move from the home pose to one 0.3 m higher with a 0.1 rad roll, with the
 * limits a 1 kHz / 200 kHz controller derives from the default parameter set (fw_limits_from_params,
 * as the board and the simulator run).
 *
 * Usage:
 *   kin-icount list   one line per figure: figure,NAME,MEASURE_FN,LOOP_FN,CALLS
 *                     (LOOP_FN is the loop-overhead measure, "-" when there is none; CALLS is
 *                     how many operations one call of MEASURE_FN performs)
 *   kin-icount FN     the set-up, then measure function FN once
 *   kin-icount        the set-up, then every measure once, and the list
 * Exit status 0, or 1 on a set-up error or an unknown FN.  Nothing here is timed. */
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <math.h>

#include "fw/limits.h"
#include "fw/move.h"
#include "fw/params.h"
#include "kin_icount.h"

enum { POSES = 2000, CONTROL_HZ = 1000, STEP_HZ = 200000 };

/* Which of the library's two x86-64 builds of tse_ik and FK's step this CPU runs
 * (kinematics/src/kin_internal.h, TSE_FMA_CLONES): the loader picks the same one. */
static const char *counted_build(void)
{
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(TSE_NO_FMA_CLONES)
    if (__builtin_cpu_supports("fma"))
        return "fused multiply-add (this CPU has FMA; scripts/kin_icount.sh --baseline counts the baseline build)";
    return "baseline x86-64 (this CPU has no FMA)";
#else
    return "baseline (built without the FMA clones)";
#endif
}

#define NOINLINE __attribute__((noinline))

/* The move planning's state, filled by plan_setup. */
static struct {
    tse_geometry g;
    fw_limits lim;
    tse_real from[6], to[6], q_from[6];
    uint32_t segments;
} mv_st;

static volatile uint32_t icount_sink;

/* Exported (not static) so that callgrind finds it by this name whatever the compiler does. */
void measure_validate_segment(void);

/* One planning of the move: its validation walks every segment. */
NOINLINE void measure_validate_segment(void)
{
    fw_move mv;
    fw_plan_result res;
    const int rc = fw_move_plan(&mv, &mv_st.g, &mv_st.lim, mv_st.from, mv_st.to, FW_MOVE_DURATION, TSE_R(5.0),
                                mv_st.q_from, &res);
    icount_sink = rc == 0 ? mv.segments : 0;
}

static int plan_setup(void)
{
    fw_param_set ps;
    fw_params_default(&ps);
    if (fw_limits_from_params(&ps, STEP_HZ, CONTROL_HZ, &mv_st.g, &mv_st.lim) != 0)
        return -1;
    for (int k = 0; k < 6; ++k)
        mv_st.from[k] = mv_st.to[k] = mv_st.g.home_pose[k];
    mv_st.to[TSE_Z] += TSE_R(0.3);
    mv_st.to[TSE_ROLL] += TSE_R(0.1);
    tse_ik_result r;
    if (tse_ik(&mv_st.g, mv_st.from, NULL, &r) != TSE_OK)
        return -1;
    memcpy(mv_st.q_from, r.q, sizeof mv_st.q_from);
    /* Once outside the measure: the segment count, and first-call costs out of the way. */
    fw_move mv;
    fw_plan_result res;
    if (fw_move_plan(&mv, &mv_st.g, &mv_st.lim, mv_st.from, mv_st.to, FW_MOVE_DURATION, TSE_R(5.0), mv_st.q_from,
                     &res) != 0) {
        fprintf(stderr, "kin-icount: the move is refused (reason %d, status %d, segment %u)\n", (int)res.reason,
                (int)res.status, (unsigned)res.segment);
        return -1;
    }
    mv_st.segments = mv.segments;
    return 0;
}

typedef struct {
    const char *name, *measure, *loop;
    void (*fn)(void), (*loop_fn)(void);
    long calls;
} figure;

int main(int argc, char **argv)
{
    static double poses[POSES][6];
    for (int k = 0; k < POSES; ++k) {
        const double t = 0.002 * (double)k;
        poses[k][0] = 0.15 * sin(t);
        poses[k][1] = 0.12 * sin(1.7 * t);
        poses[k][2] = 1.0 + 0.3 * sin(0.5 * t);
        poses[k][3] = 0.08 * sin(1.3 * t);
        poses[k][4] = 0.06 * sin(0.9 * t);
        poses[k][5] = 0.2 * sin(0.7 * t);
    }
    const int rej_d = kin_icount_double_setup((const double(*)[6])poses, POSES);
    const int rej_f = kin_icount_float_setup((const double(*)[6])poses, POSES);
    if (rej_d < 0 || rej_f < 0 || plan_setup() != 0) {
        fprintf(stderr, "kin-icount: set-up failed\n");
        return 1;
    }

#define FIG(name, calls) {#name, "measure_" #name, "measure_loop_" #name, measure_##name, measure_loop_##name, calls}
    const figure figs[] = {
        FIG(ik_double_warm, POSES),
        FIG(ik_double_cold, POSES),
        FIG(ik_float_warm, POSES),
        FIG(fk_double_warm, POSES - 1),
        {"validate_segment", "measure_validate_segment", "-", measure_validate_segment, NULL, mv_st.segments},
        FIG(ik_float_cold, POSES),
        FIG(fk_float_warm, POSES - 1),
    };
#undef FIG
    const int nfig = (int)(sizeof figs / sizeof figs[0]);

    if (argc > 2) {
        fprintf(stderr, "usage: %s [list | MEASURE_FUNCTION]\n", argv[0]);
        return 1;
    }
    if (argc == 2 && strcmp(argv[1], "list") != 0) {
        for (int i = 0; i < nfig; ++i) {
            if (strcmp(argv[1], figs[i].measure) == 0) {
                figs[i].fn();
                return 0;
            }
            if (figs[i].loop_fn && strcmp(argv[1], figs[i].loop) == 0) {
                figs[i].loop_fn();
                return 0;
            }
        }
        fprintf(stderr, "kin-icount: no measure function %s (see `%s list`)\n", argv[1], argv[0]);
        return 1;
    }
    if (argc == 1)
        for (int i = 0; i < nfig; ++i) {
            figs[i].fn();
            if (figs[i].loop_fn)
                figs[i].loop_fn();
        }
    printf("# poses the warm inverse kinematics rejects on the path: double %d, float %d\n", rej_d, rej_f);
    printf("# build: %s\n", counted_build());
    printf("# move: home to +0.3 m and 0.1 rad roll in 5 s, %u segments at %d Hz\n", (unsigned)mv_st.segments,
           CONTROL_HZ);
    for (int i = 0; i < nfig; ++i)
        printf("figure,%s,%s,%s,%ld\n", figs[i].name, figs[i].measure, figs[i].loop, figs[i].calls);
    return 0;
}
