/* The SPSC frame ring: order, the full and empty edges, wrap-around of the slots and of the
 * free-running counters, drop counting, and two threads (one pushing, one popping) passing a
 * million numbered frames: each arrives once, in order. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>
#include <pthread.h>
#include <string.h>

#include "hal_stm32f4/can_ring.h"

/* A frame that carries its sequence number everywhere it can: id, len and all 8 bytes. */
static hal_can_frame numbered(uint32_t n)
{
    hal_can_frame f;
    f.id = (uint16_t)(n & 0x7FFu);
    f.len = (uint8_t)(n % 9u);
    for (unsigned i = 0; i < 8; ++i)
        f.data[i] = (uint8_t)(n >> (8u * (i & 3u)) ^ i);
    return f;
}

static void assert_numbered(const hal_can_frame *f, uint32_t n)
{
    const hal_can_frame e = numbered(n);
    assert_int_equal(f->id, e.id);
    assert_int_equal(f->len, e.len);
    assert_memory_equal(f->data, e.data, 8);
}

static void fifo_order_and_edges(void **state)
{
    (void)state;
    static can_ring r;
    can_ring_init(&r);
    hal_can_frame f;
    assert_false(can_ring_pop(&r, &f));
    assert_int_equal(can_ring_count(&r), 0);
    for (uint32_t i = 0; i < CAN_RING_CAPACITY; ++i) {
        const hal_can_frame in = numbered(i);
        assert_true(can_ring_push(&r, &in));
    }
    assert_int_equal(can_ring_count(&r), CAN_RING_CAPACITY);
    const hal_can_frame extra = numbered(999);
    assert_false(can_ring_push(&r, &extra)); /* full: refused and counted */
    assert_false(can_ring_push(&r, &extra));
    assert_int_equal(can_ring_dropped(&r), 2);
    for (uint32_t i = 0; i < CAN_RING_CAPACITY; ++i) {
        assert_true(can_ring_pop(&r, &f));
        assert_numbered(&f, i); /* the refused frame never appears */
    }
    assert_false(can_ring_pop(&r, &f));
    assert_int_equal(can_ring_count(&r), 0);
    assert_int_equal(can_ring_dropped(&r), 2);
    can_ring_init(&r);
    assert_int_equal(can_ring_dropped(&r), 0);
}

/* Fill levels that vary from 0 to full, so the slot index passes the end of the array many
 * times at every offset. */
static void wrap_around(void **state)
{
    (void)state;
    static can_ring r;
    can_ring_init(&r);
    uint32_t in = 0, out = 0;
    hal_can_frame f;
    for (uint32_t round = 0; round < 500; ++round) {
        const uint32_t push = round % (CAN_RING_CAPACITY + 1u);
        for (uint32_t i = 0; i < push; ++i) {
            const hal_can_frame g = numbered(in);
            const int ok = can_ring_push(&r, &g);
            assert_int_equal(ok, in - out < CAN_RING_CAPACITY);
            in += (uint32_t)ok;
        }
        const uint32_t pop = (round * 7u) % (CAN_RING_CAPACITY + 1u);
        for (uint32_t i = 0; i < pop && out < in; ++i) {
            assert_true(can_ring_pop(&r, &f));
            assert_numbered(&f, out++);
        }
        assert_int_equal(can_ring_count(&r), in - out);
    }
    while (can_ring_pop(&r, &f))
        assert_numbered(&f, out++);
    assert_int_equal(out, in);
    assert_true(in > 10u * CAN_RING_CAPACITY);
}

/* The counters are free-running: start them just below 2^32 so they wrap mid-test. */
static void counter_wrap(void **state)
{
    (void)state;
    static can_ring r;
    can_ring_init(&r);
    atomic_store(&r.head, UINT32_MAX - 5u);
    atomic_store(&r.tail, UINT32_MAX - 5u);
    hal_can_frame f;
    for (uint32_t i = 0; i < CAN_RING_CAPACITY; ++i) {
        const hal_can_frame g = numbered(i);
        assert_true(can_ring_push(&r, &g));
    }
    const hal_can_frame g = numbered(77);
    assert_false(can_ring_push(&r, &g)); /* still full across the wrap */
    assert_int_equal(can_ring_count(&r), CAN_RING_CAPACITY);
    for (uint32_t i = 0; i < CAN_RING_CAPACITY; ++i) {
        assert_true(can_ring_pop(&r, &f));
        assert_numbered(&f, i);
    }
    assert_false(can_ring_pop(&r, &f));
}

/* ---- two threads ---- */

enum { STRESS_FRAMES = 1000000 };

typedef struct {
    can_ring ring;
    int drop_when_full; /* 1: like an interrupt, give up (and count); 0: retry like a sender */
    uint32_t pushed;    /* producer: frames accepted */
    atomic_int done;    /* producer: finished (release), so `pushed` is final */
} stress;

static void *producer(void *arg)
{
    stress *s = arg;
    for (uint32_t n = 0; n < STRESS_FRAMES;) {
        const hal_can_frame f = numbered(s->pushed);
        if (can_ring_push(&s->ring, &f)) {
            ++s->pushed;
            ++n;
        } else if (s->drop_when_full) {
            ++n;
        }
    }
    atomic_store_explicit(&s->done, 1, memory_order_release);
    return NULL;
}

static void check_next(const hal_can_frame *f, uint32_t *next)
{
    const hal_can_frame e = numbered(*next);
    if (f->id != e.id || f->len != e.len || memcmp(f->data, e.data, 8) != 0)
        fail_msg("frame %u out of order or torn", (unsigned)*next);
    ++*next;
}

/* Consumes until the producer is done and the ring is empty; every frame must be the next
 * number (frames refused while full were never numbered, so the sequence has no gaps). */
static uint32_t consume(stress *s)
{
    uint32_t next = 0;
    hal_can_frame f;
    for (;;) {
        if (can_ring_pop(&s->ring, &f)) {
            check_next(&f, &next);
        } else if (atomic_load_explicit(&s->done, memory_order_acquire)) {
            while (can_ring_pop(&s->ring, &f)) /* pushed before `done` */
                check_next(&f, &next);
            return next;
        }
    }
}

static void two_threads(int drop_when_full)
{
    static stress s;
    memset(&s, 0, sizeof s);
    can_ring_init(&s.ring);
    atomic_init(&s.done, 0);
    s.drop_when_full = drop_when_full;
    pthread_t t;
    assert_int_equal(pthread_create(&t, NULL, producer, &s), 0);
    const uint32_t got = consume(&s);
    assert_int_equal(pthread_join(t, NULL), 0);
    hal_can_frame f;
    assert_false(can_ring_pop(&s.ring, &f));
    assert_int_equal(got, s.pushed);
    if (drop_when_full) /* every frame either passed or was counted */
        assert_int_equal(s.pushed + can_ring_dropped(&s.ring), STRESS_FRAMES);
    else /* every frame passed (each refused attempt, retried, counts as a drop) */
        assert_int_equal(s.pushed, STRESS_FRAMES);
}

static void stress_blocking_producer(void **state)
{
    (void)state;
    two_threads(0);
}

static void stress_dropping_producer(void **state)
{
    (void)state;
    two_threads(1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(fifo_order_and_edges), cmocka_unit_test(wrap_around),
        cmocka_unit_test(counter_wrap), cmocka_unit_test(stress_blocking_producer),
        cmocka_unit_test(stress_dropping_producer),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
