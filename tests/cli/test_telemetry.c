/* tsectl's telemetry reader (host_tools/tsectl/telemetry.h) on frame sequences written out by
 * hand: a period's slides and pose are taken together, in the controller's order; a frame lost,
 * or a reader that starts in the middle of a period, never pairs the slides of one period with
 * the pose of another. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "telemetry.h"

/* Frame `m` of period `p`: every field carries the period's number, so a mix shows. */
static proto_message frame(proto_msg m, int p)
{
    proto_message f;
    memset(&f, 0, sizeof f);
    f.msg = m;
    f.node = 1;
    f.v[0] = f.v[1] = p * 1000;
    return f;
}

/* Feeds periods `from` .. `to`, leaving out frame `skip` (-1: none) of period `skip_in`; returns
 * how many poses completed and the period of the last one's slides and pose. */
static int feed(telemetry *t, int from, int to, int skip, int skip_in, int *slides_p, int *pose_p)
{
    static const proto_msg order[6] = {PM_SLIDES_A, PM_SLIDES_B, PM_SLIDES_C, PM_FK_A, PM_FK_B, PM_FK_C};
    int done = 0;
    for (int p = from; p <= to; ++p)
        for (int k = 0; k < 6; ++k) {
            if (p == skip_in && k == skip)
                continue;
            const proto_message f = frame(order[k], p);
            if (telemetry_take(t, &f)) {
                ++done;
                *slides_p = (int)(t->slides[5] * PROTO_NM_PER_M / 1000 + 0.5);
                *pose_p = (int)(t->pose[5] * PROTO_URAD_PER_RAD / 1000 + 0.5);
            }
        }
    return done;
}

/* feed(), then: `done` poses completed, the last one's slides and pose both of period `last`. */
static void expect_fed(telemetry *t, int from, int to, int skip, int skip_in, int done, int last)
{
    int s = -1, p = -1;
    assert_int_equal(feed(t, from, to, skip, skip_in, &s, &p), done);
    assert_int_equal(s, last);
    assert_int_equal(p, last);
}

static void whole_periods_pair_their_own_frames(void **state)
{
    (void)state;
    telemetry t = {0};
    expect_fed(&t, 1, 5, -1, 0, 5, 5);
}

static void a_lost_frame_drops_its_period_only(void **state)
{
    (void)state;
    for (int skip = 0; skip < 6; ++skip) {
        telemetry t = {0};
        /* Period 2 loses one frame: periods 1 and 3 complete, each with its own slides. */
        expect_fed(&t, 1, 2, skip, 2, 1, 1);
        assert_false(telemetry_has_pose(&t) && telemetry_has_slides(&t));
        expect_fed(&t, 3, 3, -1, 0, 1, 3);
    }
}

/* A reader that starts after a period's slides went by (its first frame FK_A) takes no pose
 * until a whole period: before, the pose of period 7 completed beside the slides of none. */
static void a_reader_starting_mid_period_waits_for_a_whole_one(void **state)
{
    (void)state;
    static const proto_msg tail[3] = {PM_FK_A, PM_FK_B, PM_FK_C};
    telemetry t = {0};
    for (int k = 0; k < 3; ++k) {
        const proto_message f = frame(tail[k], 7);
        assert_int_equal(telemetry_take(&t, &f), 0);
    }
    assert_false(telemetry_has_pose(&t));
    expect_fed(&t, 8, 8, -1, 0, 1, 8);
}

/* Not homed: the slides alone, period after period. */
static void slides_alone_before_homing(void **state)
{
    (void)state;
    static const proto_msg slides[3] = {PM_SLIDES_A, PM_SLIDES_B, PM_SLIDES_C};
    telemetry t = {0};
    for (int p = 1; p <= 3; ++p)
        for (int k = 0; k < 3; ++k) {
            const proto_message f = frame(slides[k], p);
            assert_int_equal(telemetry_take(&t, &f), 0);
            assert_int_equal(telemetry_has_slides(&t), k == 2);
        }
    assert_false(telemetry_has_pose(&t));
    assert_true(t.slides[0] * PROTO_NM_PER_M > 2999.5 && t.slides[0] * PROTO_NM_PER_M < 3000.5);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(whole_periods_pair_their_own_frames),
        cmocka_unit_test(a_lost_frame_drops_its_period_only),
        cmocka_unit_test(a_reader_starting_mid_period_waits_for_a_whole_one),
        cmocka_unit_test(slides_alone_before_homing),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
