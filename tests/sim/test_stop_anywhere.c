/* A STOP at any instant of a motion brings the slides to rest within the limits the plant checks
 * (the rig fails on any breach), along the path they were on:
 *   - homing's final joint move (the slides from their switches to the home pose, at 90 % of the
 *     acceleration limit): its first ramp in 5 ms steps, the cruise in 100 ms steps, the last
 *     ramp in 10 ms steps;
 *   - a move with a second one committed during it and blended into its end: every 20 ms from
 *     the second's commit to the end of both, every 5 ms while both run;
 *   - moves, one with short ramps and some as fast as the slide limits allow: every 5 ms for
 *     0.4 s, then every 100 ms.
 * The soak found all three: a stop in the first ramp of the joint move or of a move braked
 * beyond the acceleration limit (its ramp was sized from the present speed, which goes on growing
 * along an accelerating path), and a stop once the blend had begun dropped the second move and
 * sent the slides back to the first move's path at once. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "sim_rig.h"

static sim_rig R, here;
static bool homing; /* the stops are of a homing: none may leave a zero */

/* A STOP now and the wait for rest, on a copy: the rig is back as it was afterwards (every pointer
 * in the rig is into itself, so a copy back restores it). */
static void stop_here(uint32_t ms)
{
    here = R;
    rig_cmd(&R, PM_STOP);
    rig_run(&R, 1);
    /* (Or, at the very end, the last setpoints were already stepping out: nothing to stop.) */
    if (fw_state_of(R.fw) != FW_STATE_STOPPING && !(fw_state_of(R.fw) == FW_STATE_MOVING && rig_now(&R).src == FW_SRC_NONE))
        fail_msg("STOP %u ms in: state %d, src %d, tau %.4f", ms, fw_state_of(R.fw), rig_now(&R).src, (double)rig_now(&R).tau);
    if (!rig_until(&R, FW_STATE_IDLE, 10000))
        fail_msg("STOP %u ms in: state %d, fault %d", ms, fw_state_of(R.fw), fw_fault_of(R.fw));
    if (homing && fw_homed_of(R.fw))
        fail_msg("STOP %u ms in: a homing stopped short set a zero", ms);
    R = here;
}

static void test_stop_anywhere_in_homing(void **state)
{
    (void)state;
    rig_boot(&R, 0.205);
    rig_cmd(&R, PM_ENABLE);
    rig_run(&R, 10);
    rig_cmd(&R, PM_HOME);
    for (int t = 0; t < 60000 && rig_now(&R).src != FW_SRC_JOINT; ++t)
        rig_run(&R, 1);
    assert_int_equal(rig_now(&R).src, FW_SRC_JOINT);
    homing = true;
    const uint32_t T = (uint32_t)(rig_now(&R).joint_T * 1000.0), Ta = (uint32_t)(rig_now(&R).joint_Ta * 1000.0);
    unsigned stops = 0;
    for (uint32_t ms = 0, step; ms < T; ms += step) {
        stop_here(ms);
        ++stops;
        step = ms < Ta + 50u ? 5u : ms + 300u < T ? 100u : 10u;
        rig_run(&R, step);
    }
    homing = false;
    print_message("%u stops in a %u ms joint move (ramps of %u ms): all within the limits, none homed\n", stops, T, Ta);
    assert_true(stops > 60);
}

static void test_stop_anywhere_in_a_blend(void **state)
{
    (void)state;
    static const double a[6] = {0.08, 0.0, 1.0, 0.0, 0.0, 0.1}, b[6] = {0.08, 0.1, 1.1, 0.05, 0.0, 0.0};
    homing = false;
    rig_boot(&R, 0.205);
    rig_home(&R);
    rig_move(&R, a, 1500);
    rig_run(&R, 300);
    rig_move(&R, b, 1500);
    rig_run(&R, 1);
    assert_true(rig_now(&R).has_next);
    const uint32_t k0 = rig_now(&R).blend_k0, T = (uint32_t)((rig_now(&R).blend_k0 / 1000.0 + rig_now(&R).next.prof.T) * 1000.0) -
                                             rig_now(&R).segments_run;
    assert_true(k0 < rig_now(&R).move.segments); /* blended, not back to back */
    unsigned stops = 0, in_blend = 0;
    for (uint32_t ms = 0, step; ms < T; ms += step) {
        const bool overlap = rig_now(&R).has_next && rig_now(&R).tau >= k0 / 1000.0; /* both moves running */
        in_blend += overlap;
        stop_here(ms);
        ++stops;
        step = overlap ? 5u : 20u;
        rig_run(&R, step);
    }
    print_message("%u stops along two blended moves (%u while both ran): all within the limits\n", stops,
                  in_blend);
    assert_true(in_blend > 50);
}

/* Moves from the home pose, as fast as the limits let them (1 ms asked: stretched to the slide
 * limits) and one of a few seconds with short ramps (the soak's: a stop in its first ramp braked
 * at 1.13 times the limit), a STOP every 5 ms for their first 0.4 s, then every 100 ms. */
static void test_stop_anywhere_in_moves(void **state)
{
    (void)state;
    static const struct {
        double to[6];
        int32_t ms;
    } moves[] = {
        {{0.090682, 0.004854, 1.249514, -0.008245, -0.022003, 0.008081}, 2354},
        {{0.0, 0.0, 1.45, 0.0, 0.0, 0.0}, 1},     /* every slide 14 cm down */
        {{0.12, -0.1, 0.9, 0.1, -0.1, 0.3}, 1},   /* a bit of everything */
        {{-0.15, 0.1, 0.7, -0.05, 0.08, -0.3}, 1},
    };
    homing = false;
    rig_boot(&R, 0.205);
    rig_home(&R);
    const sim_rig home = R;
    unsigned stops = 0;
    for (size_t i = 0; i < sizeof moves / sizeof moves[0]; ++i) {
        R = home;
        const unsigned from = R.nlog;
        const uint8_t s = rig_move(&R, moves[i].to, moves[i].ms);
        rig_run(&R, 1);
        assert_int_equal(rig_answer(&R, from, proto_table[PM_MOVE_COMMIT].function, s, NULL), 'a');
        const uint32_t T = (uint32_t)(rig_now(&R).move.prof.T * 1000.0);
        print_message("move %zu: %.3f s, ramps of %.3f s\n", i + 1, (double)rig_now(&R).move.prof.T, (double)rig_now(&R).move.prof.Ta);
        for (uint32_t ms = 0, step; ms < T; ms += step) {
            stop_here(ms);
            ++stops;
            step = ms < 400u ? 5u : 100u;
            rig_run(&R, step);
        }
    }
    print_message("%u stops along 4 moves: all within the limits\n", stops);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_stop_anywhere_in_homing),
        cmocka_unit_test(test_stop_anywhere_in_a_blend),
        cmocka_unit_test(test_stop_anywhere_in_moves),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
