/* What one MOVE_COMMIT may cost (fw/validate.h, FW_VALIDATE_WORK; docs/validation.md, "What one
 * frame costs"), whatever the move's duration (issue 24, point 1), and the segment count checked
 * before it is converted (point 3):
 * - a move to a pose out of reach is refused at the first failing point the per-segment walk
 *   finds, with work that does not grow with its duration: 1 s or an hour, the same few hundred
 *   solves (the walk before the fix solved every segment up to the failure: 3.6 million at an
 *   hour, seconds on the board, past its watchdog);
 * - a move that would last longer than FW_MOVE_MAX_S (a move of metres at micrometres a second:
 *   4.47e9 segments, beyond a uint32_t) is refused TOO_LONG, field 0, where 3600, before its segment
 *   count is converted (UBSan's float-cast-overflow in the asan preset catches the conversion);
 * - over the wire, that refusal is a REJECT too_long naming the longest a move may last. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include <cmocka.h>

#include "fw/move.h"
#include "fw/validate.h"
#include "harness.h"

static const fw_limits LIM = {0.2, 1.0, 0.3, 1.0, 10.0, 0.5, 2.0, 1000.0, FW_LIMIT_SLIDE_VMAX};

/* fw_validate, its work summed over the planner's rounds. */
static uint32_t work;
static int counted(const fw_move *mv, const tse_geometry *g, const fw_limits *lim, const tse_real q_from[6],
                   fw_validation *v, fw_plan_result *res)
{
    const int rc = fw_validate(mv, g, lim, q_from, v, res);
    work += fw_validation_work(v);
    return rc;
}

/* The default design, the home pose's slides in home_q, and `to` the home pose moved to x, y. */
static void geometry(tse_geometry *g, double home_q[6], double to[6], double x, double y)
{
    tse_params p;
    tse_params_default(&p);
    assert_int_equal(tse_geometry_init(g, &p), TSE_PARAM_OK);
    tse_ik_result r;
    assert_int_equal(tse_ik(g, g->home_pose, NULL, &r), TSE_OK);
    for (int k = 0; k < 6; ++k) {
        home_q[k] = r.q[k];
        to[k] = g->home_pose[k];
    }
    to[0] = x;
    to[1] = y;
}

/* Along x from home to 0.6 m, out of reach (the path leaves the workspace 85 % of the way, near
 * x = 0.51 m), over durations from 1 s to the longest a move may last. */
static void test_refusal_work_does_not_grow_with_duration(void **state)
{
    (void)state;
    tse_geometry g;
    double q0[6], to[6];
    geometry(&g, q0, to, 0.6, 0.0);
    static const double durations[] = {1.0, 10.0, 100.0, 1000.0, 3600.0};
    uint32_t most = 0, least = UINT32_MAX;
    for (size_t i = 0; i < sizeof durations / sizeof durations[0]; ++i) {
        static fw_move mv, walk;
        fw_plan_result res, rw;
        work = 0;
        assert_int_equal(fw_move_plan_by(&mv, &g, &LIM, g.home_pose, to, FW_MOVE_DURATION, durations[i], q0, &res,
                                         counted),
                         -1);
        assert_int_equal(res.reason, FW_REASON_KINEMATICS);
        printf("%.0f s: refused at segment %u of %u (u %.4f), work %u solves\n", durations[i], res.segment,
               mv.segments, res.where, work);
        if (work > most)
            most = work;
        if (work < least)
            least = work;
        /* Where the per-segment walk refuses it (walked here up to 100 s: 100,000 solves). */
        if (durations[i] <= 100.0) {
            assert_int_equal(fw_move_plan_by(&walk, &g, &LIM, g.home_pose, to, FW_MOVE_DURATION, durations[i], q0,
                                             &rw, fw_validate_per_segment),
                             -1);
            assert_int_equal(rw.reason, FW_REASON_KINEMATICS);
            assert_int_equal(res.segment, rw.segment);
            assert_int_equal(res.status, rw.status);
            assert_int_equal(res.scissor, rw.scissor);
        }
    }
    /* The path leaves the workspace 85 % of the way along, so a walk to it solves 85 % of the
     * segments: 2,000 at 1 s, 3 million at an hour.  Bounded, the work is that of a short move. */
    assert_true(most <= FW_VALIDATE_WORK);
    assert_true(most <= 4u * least);
}

/* 1 um/s from home to x = 4 m, y = -2 m: 4.47 m at 1e-6 m/s, 4.47e6 s, 4.47e9 segments. */
static void test_too_long_in_time(void **state)
{
    (void)state;
    tse_geometry g;
    double q0[6], to[6];
    geometry(&g, q0, to, 4.0, -2.0);
    static fw_move mv;
    fw_plan_result res;
    work = 0;
    assert_int_equal(fw_move_plan_by(&mv, &g, &LIM, g.home_pose, to, FW_MOVE_SPEED, 1e-6, q0, &res, counted), -1);
    assert_int_equal(res.reason, FW_REASON_TOO_LONG);
    assert_int_equal(res.status, TSE_OK);
    assert_true(res.where == (double)FW_MOVE_MAX_S);
    assert_int_equal(work, 0); /* refused before any validation */
    /* An hour exactly is a move; a millisecond more is not (at 1 mm/s over 3.6 m and a bit). */
    to[0] = g.home_pose[0] + 3.6;
    to[1] = g.home_pose[1];
    assert_int_equal(fw_move_plan_by(&mv, &g, &LIM, g.home_pose, to, FW_MOVE_SPEED, 0.99e-3, q0, &res, counted), -1);
    assert_int_equal(res.reason, FW_REASON_TOO_LONG);
}

/* Over the wire: REJECT too_long, field 0, where 3600, for MOVE_COMMIT at 1 um/s. */
static void test_too_long_rejected(void **state)
{
    (void)state;
    reach(FW_STATE_IDLE);
    double to[6];
    for (int k = 0; k < 6; ++k)
        to[k] = fw_geometry_of(C)->home_pose[k];
    to[0] = 4.0;
    to[1] = -2.0;
    const unsigned from = F.tx_count;
    const uint8_t s = seq++;
    stage(s, to);
    send(PM_MOVE_COMMIT, (const int32_t[]){s, 1, 1});
    fw_poll(C);
    const proto_message r = reject_of(from, proto_table[PM_MOVE_COMMIT].function);
    assert_int_equal(r.v[1], s);
    assert_int_equal(r.v[2], FW_REASON_TOO_LONG);
    assert_int_equal(r.v[3], 0);
    assert_int_equal(r.v[4], 0);
    assert_int_equal(r.v[5], 0);
    assert_int_equal(r.v[6], FW_MOVE_MAX_S);
    assert_int_equal(fw_state_of(C), FW_STATE_IDLE);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_refusal_work_does_not_grow_with_duration),
        cmocka_unit_test(test_too_long_in_time),
        cmocka_unit_test(test_too_long_rejected),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
