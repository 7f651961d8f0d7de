/* MOVE_INFO, the frame after a move's ACK: it follows the ACK at once, carries the commit's
 * sequence number, and says how the move starts (from rest, blended into the running move, or
 * after it) and what set its pace, on the board as on the simulator. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "harness.h"

/* The MOVE_INFO since tx index `from`, decoded; it must come right after the ACK of MOVE_COMMIT. */
static proto_message info_since(unsigned from)
{
    for (unsigned i = from; i < F.tx_count; ++i) {
        proto_message m;
        if (proto_decode(&F.tx[i], PROTO_TO_HOST, &m).reason != FW_REASON_NONE || m.msg != PM_ACK ||
            m.v[0] != proto_table[PM_MOVE_COMMIT].function)
            continue;
        assert_true(i + 1 < F.tx_count);
        proto_message info;
        assert_int_equal(proto_decode(&F.tx[i + 1], PROTO_TO_HOST, &info).reason, FW_REASON_NONE);
        assert_int_equal(info.msg, PM_MOVE_INFO);
        assert_int_equal(info.v[0], m.v[1]); /* the ACK's sequence number */
        return info;
    }
    fail_msg("no ACK of MOVE_COMMIT");
    proto_message none = {0};
    return none;
}

static void from_rest_then_blended(void **state)
{
    (void)state;
    reach(FW_STATE_IDLE);
    const double first[6] = {0.06, 0.0, 1.05, 0, 0, 0}, second[6] = {0.06, 0.06, 1.10, 0, 0, 0.05};
    unsigned from = F.tx_count;
    move_to(first, 1500);
    run(10);
    proto_message info = info_since(from);
    assert_int_equal(info.v[1], FW_START_REST);
    /* 1.5 s for a few centimetres: the request is the pace, no slide demand. */
    assert_int_equal(info.v[2], FW_BOUND_ASKED);
    assert_int_equal(info.v[3], 0);
    assert_int_equal(info.v[4], 0);
    run(200);
    from = F.tx_count;
    move_to(second, 1500);
    run(10);
    info = info_since(from);
    assert_int_equal(info.v[1], FW_START_BLENDED);
    assert_true(now().blend_k0 < now().move.segments);
    for (int i = 0; i < 400 && fw_state_of(C) != FW_STATE_IDLE; ++i)
        run(10);
}

/* Committed in the first move's last few milliseconds, too late to overlap its deceleration: the
 * second runs after it. */
static void too_late_to_blend_runs_after(void **state)
{
    (void)state;
    reach(FW_STATE_IDLE);
    const double first[6] = {0.06, 0.0, 1.05, 0, 0, 0}, second[6] = {0.0, 0.0, 1.0, 0, 0, 0};
    move_to(first, 1000);
    run(10);
    const uint32_t end = now().move.segments;
    for (int i = 0; i < 5000 && fw_state_of(C) == FW_STATE_MOVING && now().segments_run + 5u < end; ++i) {
        heartbeat();
        fake_run(&F, C, 1);
    }
    assert_int_equal(fw_state_of(C), FW_STATE_MOVING);
    assert_true(now().segments_run + 5u >= end);
    const unsigned from = F.tx_count;
    move_to(second, 1000);
    fw_poll(C);
    const proto_message info = info_since(from);
    assert_int_equal(info.v[1], FW_START_AFTER);
    assert_int_equal(now().blend_k0, now().move.segments);
    for (int i = 0; i < 400 && fw_state_of(C) != FW_STATE_IDLE; ++i)
        run(10);
}

/* A move asked faster than the slide limits allow names the slide that stretched it and its
 * demand over the limit in effect: at the harness's 100 kHz the step generator's 68.9 mm/s
 * (test_limits.c), not slide_vmax's 150. */
static void stretched_names_the_slide(void **state)
{
    (void)state;
    reach(FW_STATE_IDLE);
    const double far[6] = {0.1, -0.05, 1.3, 0.05, -0.05, 0.2};
    const unsigned from = F.tx_count;
    move_to(far, 100);
    run(10);
    const proto_message info = info_since(from);
    assert_int_equal(info.v[1], FW_START_REST);
    assert_true(info.v[2] == FW_BOUND_STEP_GENERATOR || info.v[2] == FW_BOUND_SLIDE_AMAX);
    assert_in_range(info.v[3], 1, 6);
    assert_true(info.v[4] > 1000);
    assert_true(now().move.prof.T > 0.1);
}

/* A speed-bound stretch (the acceleration limit raised to 20 m/s^2 out of the way) names the
 * limit in effect: the step generator's at the defaults, slide_vmax once it is the lower. */
static void stretched_names_the_speed_limit(void **state)
{
    (void)state;
    static const struct {
        int32_t slide_vmax;
        fw_move_bound bound;
    } cases[] = {{150000, FW_BOUND_STEP_GENERATOR}, {40000, FW_BOUND_SLIDE_VMAX}};
    for (size_t i = 0; i < 2; ++i) {
        reach(FW_STATE_DISABLED);
        assert_int_equal(set_param(FP_SLIDE_AMAX, 20000000, NULL, NULL), 'a');
        assert_int_equal(set_param(FP_SLIDE_VMAX, cases[i].slide_vmax, NULL, NULL), 'a');
        home();
        const double far[6] = {0.0, 0.0, 1.3, 0.0, 0.0, 0.0};
        const unsigned from = F.tx_count;
        move_to(far, 100);
        run(10);
        const proto_message info = info_since(from);
        assert_int_equal(info.v[2], cases[i].bound);
        assert_true(info.v[4] > 1000);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(from_rest_then_blended),
        cmocka_unit_test(too_late_to_blend_runs_after),
        cmocka_unit_test(stretched_names_the_slide),
        cmocka_unit_test(stretched_names_the_speed_limit),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
