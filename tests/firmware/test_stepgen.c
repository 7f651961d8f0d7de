/* Step generator: exact step counts, spacing, direction set-up, and the straight line between
 * setpoints, over long random runs.  Expectations come from the definitions, not the code. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "fw/stepgen.h"

enum { TICKS = 200, SETUP = 3, INTERVAL = 2 };

typedef struct {
    int32_t pos[6];       /* counted from the pulses, the way a driver would */
    int last_step[6];     /* tick of each axis' latest step */
    int last_dir_change[6];
    uint8_t forward;
    long tick;
    int setup, interval;  /* of the configuration observed */
} observer;

static void observe(observer *o, stepgen_output out)
{
    ++o->tick;
    for (int i = 0; i < 6; ++i) {
        const uint8_t bit = (uint8_t)(1u << i);
        if ((out.forward_mask ^ o->forward) & bit)
            o->last_dir_change[i] = (int)o->tick;
        if (out.step_mask & bit) {
            /* Two steps of one axis at least INTERVAL ticks apart; none within SETUP ticks of
             * a direction change (the change takes effect on its own tick). */
            assert_true(o->tick - o->last_step[i] >= o->interval);
            assert_true(o->tick - o->last_dir_change[i] >= o->setup + 1);
            o->pos[i] += (out.forward_mask & bit) ? 1 : -1;
            o->last_step[i] = (int)o->tick;
        }
    }
    o->forward = out.forward_mask;
}

static void init_cfg(stepgen *sg, observer *o, const stepgen_config *cfg)
{
    const int32_t zero[6] = {0};
    assert_int_equal(stepgen_init(sg, cfg, zero), 0);
    const int never = -1000000;
    *o = (observer){{0}, {never, never, never, never, never, never},
                    {never, never, never, never, never, never}, 0x3F, 0,
                    (int)cfg->dir_setup_ticks, (int)cfg->min_step_interval};
}

static void init(stepgen *sg, observer *o)
{
    const stepgen_config cfg = {TICKS, SETUP, INTERVAL};
    init_cfg(sg, o, &cfg);
}

/* The positions the generator reports are the pulses counted so far. */
static void expect_positions(const stepgen *sg, const observer *o)
{
    int32_t pos[6];
    stepgen_positions(sg, pos);
    assert_memory_equal(pos, o->pos, sizeof pos);
}

static void test_capacity(void **state)
{
    (void)state;
    const stepgen_config cfg = {TICKS, SETUP, INTERVAL};
    assert_int_equal(stepgen_capacity(&cfg, false), TICKS / INTERVAL);
    assert_int_equal(stepgen_capacity(&cfg, true), (TICKS - SETUP) / INTERVAL);
}

static void test_bad_config(void **state)
{
    (void)state;
    stepgen sg;
    const int32_t zero[6] = {0};
    const stepgen_config bad[] = {{0, 1, 1}, {200, 0, 1}, {200, 1, 0}, {200, 200, 1}};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i)
        assert_int_equal(stepgen_init(&sg, &bad[i], zero), -1);
}

/* Random setpoints within capacity: every segment ends exactly on its setpoint, while no
 * direction changes the count stays within half a step of the straight line, and the positions
 * read between any two ticks are the pulses emitted. */
static void test_exact_random(void **state)
{
    (void)state;
    stepgen sg;
    observer o;
    init(&sg, &o);
    srand(7);
    int32_t target[6] = {0};
    const int cap = (TICKS - SETUP) / INTERVAL;
    for (int seg = 0; seg < 20000; ++seg) {
        int32_t start[6];
        for (int i = 0; i < 6; ++i) {
            start[i] = target[i];
            target[i] += rand() % (2 * cap + 1) - cap;
        }
        assert_int_equal(stepgen_push(&sg, target), 0);
        const long first_tick = o.tick + 1;
        for (int t = 1; t <= TICKS; ++t) {
            observe(&o, stepgen_tick(&sg));
            for (int i = 0; i < 6; ++i) {
                if (o.last_dir_change[i] == first_tick)
                    continue; /* a direction change delays the axis by design */
                const double line = start[i] + (double)(target[i] - start[i]) * t / TICKS;
                assert_true(o.pos[i] - line <= 0.5 + 1e-9 && line - o.pos[i] <= 0.5 + 1e-9);
            }
            expect_positions(&sg, &o);
        }
        for (int i = 0; i < 6; ++i)
            assert_int_equal(o.pos[i], target[i]);
    }
    assert_int_equal(sg.overruns, 0);
    int32_t pos[6];
    stepgen_positions(&sg, pos);
    assert_memory_equal(pos, o.pos, sizeof pos);
}

/* The control loop keeps the queue full while the interrupt runs, refilling it in the middle of
 * segments as it does while moving: the segments run back to back, each ends exactly on its
 * setpoint, and the positions read between ticks are the pulses emitted. */
static void test_pipelined(void **state)
{
    (void)state;
    stepgen sg;
    observer o;
    init(&sg, &o);
    srand(11);
    enum { SEGMENTS = 3000, FIFO = 8 };
    int32_t fifo[FIFO][6], last[6] = {0};
    unsigned pushed = 0;
    const int cap = (TICKS - SETUP) / INTERVAL;
    for (long tick = 0; tick < (long)SEGMENTS * TICKS; ++tick) {
        if (tick % TICKS == (tick / TICKS) % TICKS) { /* a different tick of each segment */
            int32_t t[6];
            for (int i = 0; i < 6; ++i)
                t[i] = last[i] + rand() % (2 * cap + 1) - cap;
            while (stepgen_push(&sg, t) == 0) {
                memcpy(fifo[pushed++ % FIFO], t, sizeof t);
                memcpy(last, t, sizeof last);
                for (int i = 0; i < 6; ++i)
                    t[i] = last[i] + rand() % (2 * cap + 1) - cap;
            }
            assert_int_equal(stepgen_queued(&sg), STEPGEN_QUEUE);
        }
        observe(&o, stepgen_tick(&sg));
        expect_positions(&sg, &o);
        if ((tick + 1) % TICKS == 0) {
            const int32_t *want = fifo[(tick / TICKS) % FIFO];
            for (int i = 0; i < 6; ++i)
                assert_int_equal(o.pos[i], want[i]);
        }
    }
    assert_int_equal(sg.overruns, 0);
}

/* Segments longer than 32767 ticks (the positions' arithmetic widens): exact at every segment
 * end with direction changes on some axes, the positions always the pulses emitted. */
static void test_long_segments(void **state)
{
    (void)state;
    const stepgen_config cfg = {40000, 5, 3};
    stepgen sg;
    observer o;
    init_cfg(&sg, &o, &cfg);
    const int32_t cap = (int32_t)stepgen_capacity(&cfg, true);
    int32_t target[6] = {0};
    for (int seg = 0; seg < 6; ++seg) {
        for (int i = 0; i < 6; ++i)
            target[i] += ((seg + i) % 3 == 0 ? -1 : 1) * (cap - 7 * i);
        assert_int_equal(stepgen_push(&sg, target), 0);
        for (uint32_t t = 1; t <= cfg.ticks_per_segment; ++t) {
            observe(&o, stepgen_tick(&sg));
            if (t % 97 == 0 || t == cfg.dir_setup_ticks + 1)
                expect_positions(&sg, &o);
        }
        for (int i = 0; i < 6; ++i)
            assert_int_equal(o.pos[i], target[i]);
        expect_positions(&sg, &o);
    }
    assert_int_equal(sg.overruns, 0);
}

/* Asking for more than a segment holds: counted, emitted at the maximum rate, and the rest made
 * up in the following segments, so the total still arrives. */
static void test_overrun_carries(void **state)
{
    (void)state;
    stepgen sg;
    observer o;
    init(&sg, &o);
    const int32_t far[6] = {500, -500, 250, 0, 99, -100};
    assert_int_equal(stepgen_push(&sg, far), 0);
    for (int seg = 0; seg < 6; ++seg) {
        if (seg > 0)
            assert_int_equal(stepgen_push(&sg, far), 0);
        for (int t = 0; t < TICKS; ++t)
            observe(&o, stepgen_tick(&sg));
    }
    assert_true(sg.overruns >= 1);
    for (int i = 0; i < 6; ++i)
        assert_int_equal(o.pos[i], far[i]);
}

static void test_queue_and_idle(void **state)
{
    (void)state;
    stepgen sg;
    observer o;
    init(&sg, &o);
    assert_true(stepgen_idle(&sg));
    int32_t t[6] = {1, 2, 3, 4, 5, 6};
    for (int k = 0; k < STEPGEN_QUEUE; ++k)
        assert_int_equal(stepgen_push(&sg, t), 0);
    assert_int_equal(stepgen_push(&sg, t), -1);
    assert_int_equal(stepgen_queued(&sg), STEPGEN_QUEUE);
    assert_false(stepgen_idle(&sg));
    assert_int_equal(stepgen_set_position(&sg, t), -1); /* not while busy */
    for (int k = 0; k < STEPGEN_QUEUE * TICKS; ++k)
        observe(&o, stepgen_tick(&sg));
    assert_true(stepgen_idle(&sg));
    for (int i = 0; i < 6; ++i)
        assert_int_equal(o.pos[i], t[i]);
    const int32_t zero[6] = {0};
    assert_int_equal(stepgen_set_position(&sg, zero), 0);
}

/* Abort drops the running and queued segments at once and keeps the steps actually emitted. */
static void test_abort(void **state)
{
    (void)state;
    stepgen sg;
    observer o;
    init(&sg, &o);
    const int32_t t[6] = {90, 90, 90, 90, 90, 90};
    stepgen_push(&sg, t);
    stepgen_push(&sg, t);
    for (int k = 0; k < TICKS / 2; ++k)
        observe(&o, stepgen_tick(&sg));
    stepgen_abort(&sg);
    assert_true(stepgen_idle(&sg));
    for (int k = 0; k < 3 * TICKS; ++k) {
        const stepgen_output out = stepgen_tick(&sg);
        assert_int_equal(out.step_mask, 0);
    }
    int32_t pos[6];
    stepgen_positions(&sg, pos);
    assert_memory_equal(pos, o.pos, sizeof pos);
    assert_true(pos[0] > 0 && pos[0] < 90);
}

/* Halt mid-segment: not a step and no change of state for as long as it lasts, pushes only wait;
 * abort then drops all of it and ends the halt, and stepping resumes from the steps emitted. */
static void test_halt(void **state)
{
    (void)state;
    stepgen sg;
    observer o;
    init(&sg, &o);
    const int32_t t[6] = {90, -90, 90, -90, 90, -90};
    stepgen_push(&sg, t);
    for (int k = 0; k < TICKS / 2; ++k)
        observe(&o, stepgen_tick(&sg));
    assert_true(o.pos[0] > 0);
    stepgen_halt(&sg);
    const stepgen frozen = sg;
    const int32_t more[6] = {180, -180, 180, -180, 180, -180};
    assert_int_equal(stepgen_push(&sg, more), 0); /* the producer may still push */
    for (int k = 0; k < 3 * TICKS; ++k) {
        const stepgen_output out = stepgen_tick(&sg);
        assert_int_equal(out.step_mask, 0);
        assert_false(out.dir_changed);
    }
    assert_int_equal(sg.tick, frozen.tick);
    assert_int_equal(sg.cur, frozen.cur);
    assert_memory_equal(sg.ring[sg.cur].ax, frozen.ring[frozen.cur].ax, sizeof sg.ring[0].ax);
    assert_int_equal(atomic_load(&sg.tail), atomic_load(&frozen.tail));
    assert_false(stepgen_idle(&sg));
    stepgen_abort(&sg);
    assert_true(stepgen_idle(&sg));
    int32_t pos[6];
    stepgen_positions(&sg, pos);
    assert_memory_equal(pos, o.pos, sizeof pos);
    /* Not halted any more: the next setpoint is stepped, from where the slides are. */
    stepgen_push(&sg, t);
    for (int k = 0; k < TICKS; ++k)
        observe(&o, stepgen_tick(&sg));
    for (int i = 0; i < 6; ++i)
        assert_int_equal(o.pos[i], t[i]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_capacity),     cmocka_unit_test(test_bad_config),
        cmocka_unit_test(test_exact_random), cmocka_unit_test(test_pipelined),
        cmocka_unit_test(test_long_segments), cmocka_unit_test(test_overrun_carries),
        cmocka_unit_test(test_queue_and_idle), cmocka_unit_test(test_abort),
        cmocka_unit_test(test_halt),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
