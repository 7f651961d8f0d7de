/* The fault layer itself (hal/fault), on the fake HAL's bus, clock, switches and drives: each
 * fault does what fault_can.h, fault_inputs.h and fault_stepper.h promise, at the rate asked
 * (within four standard deviations of the binomial), the same again for the same seed, and the
 * frame counts always add up. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "fake_hal.h"
#include "hal_fault/fault_can.h"
#include "hal_fault/fault_inputs.h"
#include "hal_fault/fault_stepper.h"

static fake_hal F;
static fw_hal H;
static fault_can FC;
static hal_can can;

static void start(const fault_can_config *cfg)
{
    fake_hal_init(&F, &H);
    fault_can_init(&FC, cfg, H.can, H.clock);
    can = fault_can_hal(&FC);
}

/* A frame numbered n: id 0x101 (our node), n in its first two bytes. */
static void put(uint16_t n)
{
    const uint8_t d[8] = {(uint8_t)n, (uint8_t)(n >> 8), 0xA5, 0x5A, 1, 2, 3, 4};
    fake_send(&F, 0x101, 8, d);
}

static int number(const hal_can_frame *f)
{
    return f->data[0] | f->data[1] << 8;
}

/* Everything receive() hands over now, as frame numbers; returns how many. */
static int take(int *out, int cap)
{
    int n = 0;
    hal_can_frame f;
    while (can.receive(can.ctx, &f) == 1) {
        assert_true(n < cap);
        out[n++] = number(&f);
    }
    return n;
}

static void counts_add_up(void)
{
    const fault_can_stats *s = &FC.stats;
    assert_int_equal(s->received + s->faults[FAULT_DUP],
                     s->delivered + s->faults[FAULT_DROP] + s->silenced + s->bus_off_lost + FC.nheld);
}

static void test_drop_and_dup(void **state)
{
    (void)state;
    fault_can_config cfg = {.seed = 3};
    cfg.p[FAULT_DROP] = 1.0;
    start(&cfg);
    for (int i = 0; i < 10; ++i)
        put((uint16_t)i);
    int got[64];
    assert_int_equal(take(got, 64), 0);
    assert_int_equal(FC.stats.faults[FAULT_DROP], 10);
    counts_add_up();

    cfg.p[FAULT_DROP] = 0.0;
    cfg.p[FAULT_DUP] = 1.0;
    start(&cfg);
    for (int i = 0; i < 10; ++i)
        put((uint16_t)i);
    assert_int_equal(take(got, 64), 20);
    for (int i = 0; i < 10; ++i) /* each twice, the copy right after it */
        assert_true(got[2 * i] == i && got[2 * i + 1] == i);
    assert_int_equal(FC.stats.faults[FAULT_DUP], 10);
    counts_add_up();
}

static void test_reorder_and_delay(void **state)
{
    (void)state;
    fault_can_config cfg = {.seed = 3, .delay_us = 20000};
    start(&cfg);
    int got[64];
    /* Frame 1 reordered: it comes after frame 2. */
    FC.cfg.p[FAULT_REORDER] = 1.0;
    put(1);
    assert_int_equal(take(got, 64), 0);
    FC.cfg.p[FAULT_REORDER] = 0.0;
    put(2);
    assert_int_equal(take(got, 64), 2);
    assert_true(got[0] == 2 && got[1] == 1);
    /* One with no successor comes after delay_us at the latest. */
    FC.cfg.p[FAULT_REORDER] = 1.0;
    put(3);
    assert_int_equal(take(got, 64), 0); /* the layer decides as it takes a frame off the bus */
    FC.cfg.p[FAULT_REORDER] = 0.0;
    F.now_us += 19999;
    assert_int_equal(take(got, 64), 0);
    F.now_us += 1;
    assert_int_equal(take(got, 64), 1);
    assert_int_equal(got[0], 3);
    /* Delayed: held exactly delay_us, while later frames pass. */
    FC.cfg.p[FAULT_DELAY] = 1.0;
    put(4);
    assert_int_equal(take(got, 64), 0);
    FC.cfg.p[FAULT_DELAY] = 0.0;
    put(5);
    assert_int_equal(take(got, 64), 1);
    assert_int_equal(got[0], 5);
    F.now_us += 19999;
    assert_int_equal(take(got, 64), 0);
    F.now_us += 1;
    assert_int_equal(take(got, 64), 1);
    assert_int_equal(got[0], 4);
    assert_int_equal(FC.stats.faults[FAULT_REORDER], 2);
    assert_int_equal(FC.stats.faults[FAULT_DELAY], 1);
    counts_add_up();
}

static int bits(unsigned x)
{
    int n = 0;
    for (; x; x &= x - 1)
        ++n;
    return n;
}

static bool spare_odd(void *arg, const hal_can_frame *before, const hal_can_frame *after)
{
    (void)arg;
    /* Asked of a real change. */
    assert_true(before->id != after->id || before->len != after->len || memcmp(before->data, after->data, 8) != 0);
    return number(before) % 2 == 1;
}

/* Each way of corrupting changes exactly what it says; spared frames are left alone. */
static void test_corrupt(void **state)
{
    (void)state;
    const fault_corrupt_how hows[] = {FAULT_CORRUPT_PAYLOAD, FAULT_CORRUPT_LENGTH, FAULT_CORRUPT_ID};
    for (size_t h = 0; h < 3; ++h) {
        fault_can_config cfg = {.seed = 11, .corrupt_how = hows[h]};
        cfg.p[FAULT_CORRUPT] = 1.0;
        start(&cfg);
        for (int i = 0; i < 200; ++i) {
            /* Even numbers only: the number survives a flip in byte 0's high bits or byte 1. */
            const uint8_t d[8] = {(uint8_t)(2 * i), 0, 0xA5, 0x5A, 1, 2, 3, 4};
            fake_send(&F, 0x101, 8, d);
            hal_can_frame f;
            assert_int_equal(can.receive(can.ctx, &f), 1);
            int diff = 0;
            for (int b = 0; b < 8; ++b)
                diff += bits((unsigned)(f.data[b] ^ d[b]));
            if (hows[h] == FAULT_CORRUPT_PAYLOAD)
                assert_true(diff == 1 && f.len == 8 && f.id == 0x101);
            else if (hows[h] == FAULT_CORRUPT_LENGTH)
                assert_true(diff == 0 && f.len < 8 && f.id == 0x101);
            else
                assert_true(diff == 0 && f.len == 8 && bits(f.id ^ 0x101u) == 1 && f.id <= 0x7FF);
        }
        assert_int_equal(FC.stats.faults[FAULT_CORRUPT], 200);
    }
    /* Spared: odd numbers pass untouched. */
    fault_can_config cfg = {.seed = 5, .corrupt_how = FAULT_CORRUPT_PAYLOAD, .spare = spare_odd};
    cfg.p[FAULT_CORRUPT] = 1.0;
    start(&cfg);
    for (int i = 0; i < 100; ++i) {
        put((uint16_t)(2 * i + 1));
        hal_can_frame f;
        assert_int_equal(can.receive(can.ctx, &f), 1);
        assert_int_equal(number(&f), 2 * i + 1);
        assert_int_equal(f.data[2], 0xA5);
    }
    assert_int_equal(FC.stats.spared, 100);
    assert_int_equal(FC.stats.faults[FAULT_CORRUPT], 0);
}

/* drop at 10 % over 10000 frames: 1000 +- 4 sigma (sigma = 30); the same seed, the same frames
 * lost; another seed, others. */
static void test_rate_and_seed(void **state)
{
    (void)state;
    static int first[10000], second[10000];
    int n[3];
    for (int run = 0; run < 3; ++run) {
        fault_can_config cfg = {.seed = run < 2 ? 42 : 43};
        cfg.p[FAULT_DROP] = 0.1;
        start(&cfg);
        int *out = run == 0 ? first : second;
        n[run] = 0;
        for (int i = 0; i < 10000; ++i) {
            put((uint16_t)i);
            n[run] += take(out + n[run], 10000 - n[run]);
        }
        const double lost = 10000 - n[run];
        assert_true(fabs(lost - 1000.0) <= 4 * 30.0);
        assert_int_equal(FC.stats.faults[FAULT_DROP], (int)lost);
        counts_add_up();
        if (run == 1) {
            assert_int_equal(n[1], n[0]);
            assert_memory_equal(first, second, sizeof(int) * (size_t)n[0]);
        }
    }
    assert_true(n[2] != n[0] || memcmp(first, second, sizeof(int) * (size_t)n[0]) != 0);
}

static void test_silence_and_bus_off(void **state)
{
    (void)state;
    fault_can_config cfg = {.silence = {1000, 2000}, .bus_off = {5000, 6000}};
    start(&cfg);
    int got[8];
    hal_can_state st;
    put(1);
    assert_int_equal(take(got, 8), 1);
    F.now_us = 1000;
    put(2);
    assert_int_equal(take(got, 8), 0); /* lost to the silence */
    F.now_us = 2000;
    put(3);
    assert_int_equal(take(got, 8), 1);
    assert_int_equal(got[0], 3);
    assert_int_equal(FC.stats.silenced, 1);
    can.state(can.ctx, &st);
    assert_false(st.bus_off);
    assert_int_equal(st.bus_off_events, 0);

    const hal_can_frame out = {0x401, 1, {9}};
    F.now_us = 5500;
    can.state(can.ctx, &st);
    assert_true(st.bus_off && st.error_passive);
    assert_int_equal(st.bus_off_events, 1);
    assert_int_equal(can.send(can.ctx, &out), -1); /* refused, and nothing on the bus */
    assert_int_equal(F.tx_count, 0);
    put(4);
    assert_int_equal(take(got, 8), 0);
    assert_int_equal(FC.stats.bus_off_lost, 1);
    F.now_us = 6000;
    can.state(can.ctx, &st);
    assert_false(st.bus_off);
    assert_int_equal(st.bus_off_events, 1); /* still the one */
    assert_int_equal(can.send(can.ctx, &out), 0);
    assert_int_equal(F.tx_count, 1);
    /* A bus-off that began and ended between two looks still counts. */
    FC.cfg.bus_off = (fault_window){7100, 7600};
    F.now_us = 8000;
    can.state(can.ctx, &st);
    assert_false(st.bus_off);
    assert_int_equal(st.bus_off_events, 2);
    assert_int_equal(FC.stats.send_refused, 1);
    assert_int_equal(FC.stats.sent, 2);
    counts_add_up();
}

static void test_inputs(void **state)
{
    (void)state;
    fake_hal_init(&F, &H);
    F.steps[2] = 0; /* slide 3's homing switch truly pressed */
    const fault_inputs_config cfg = {.estop = {1000, 2000}, .limit = {3000, FAULT_FOREVER}, .limit_mask = 1u << 9};
    fault_inputs fi;
    fault_inputs_init(&fi, &cfg, H.inputs, H.clock);
    const hal_inputs in = fault_inputs_hal(&fi);
    assert_false(in.estop(in.ctx));
    assert_int_equal(in.limits(in.ctx), 1u << 2);
    F.now_us = 1000;
    assert_true(in.estop(in.ctx));
    F.estop_open = true; /* the true input passes as well */
    F.now_us = 2000;
    assert_true(in.estop(in.ctx));
    F.estop_open = false;
    assert_false(in.estop(in.ctx));
    F.now_us = 3000;
    assert_int_equal(in.limits(in.ctx), 1u << 2 | 1u << 9);
    F.now_us = 1000000000;
    assert_int_equal(in.limits(in.ctx), 1u << 2 | 1u << 9);
}

static void test_stepper(void **state)
{
    (void)state;
    fake_hal_init(&F, &H);
    fault_stepper_config cfg = {.stall = {1000, 2000}, .stall_mask = 1u << 1};
    cfg.miss[4] = 2;
    fault_stepper fs;
    fault_stepper_init(&fs, &cfg, H.stepper, H.clock);
    const hal_stepper st = fault_stepper_hal(&fs);
    assert_non_null(st.timing);
    int32_t s0[6];
    memcpy(s0, F.steps, sizeof s0);
    st.set_dir(st.ctx, 0x3F & ~(1u << 1)); /* slide 2 downwards */
    assert_int_equal(F.forward_mask, 0x3F & ~(1u << 1));
    st.pulse(st.ctx, 0x3F); /* before the stall: slide 5 misses its first */
    F.now_us = 1500;
    st.pulse(st.ctx, 0x3F); /* slide 2 stalled, slide 5 misses its second */
    st.pulse(st.ctx, 0x02);
    F.now_us = 2000;
    st.pulse(st.ctx, 0x3F);
    const int32_t want[6] = {3, -2, 3, 3, 1, 3};
    for (int k = 0; k < 6; ++k)
        assert_int_equal(F.steps[k] - s0[k], want[k]);
    const int64_t lost[6] = {0, 2, 0, 0, 2, 0}; /* slide 2's were downwards: -2, and taken -2 */
    for (int k = 0; k < 6; ++k)
        assert_true(fs.lost[k] == (k == 1 ? -lost[k] : lost[k]));
    assert_true(fs.lost_total == 4);
    /* Emitted = taken + lost, per slide. */
    const int32_t emitted[6] = {3, -4, 3, 3, 3, 3};
    for (int k = 0; k < 6; ++k)
        assert_true(emitted[k] == F.steps[k] - s0[k] + fs.lost[k]);
    st.enable(st.ctx, true);
    assert_true(F.enabled);
    st.timing(st.ctx, 3000, 7000);
    assert_int_equal(F.pulse_ns, 3000);
    assert_int_equal(F.dir_setup_ns, 7000);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_drop_and_dup),
        cmocka_unit_test(test_reorder_and_delay),
        cmocka_unit_test(test_corrupt),
        cmocka_unit_test(test_rate_and_seed),
        cmocka_unit_test(test_silence_and_bus_off),
        cmocka_unit_test(test_inputs),
        cmocka_unit_test(test_stepper),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
