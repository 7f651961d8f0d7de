/* The SPSC frame ring: see can_ring.h for the ordering argument. */
#include "hal_stm32f4/can_ring.h"

#define MASK (CAN_RING_CAPACITY - 1u)

void can_ring_init(can_ring *r)
{
    atomic_init(&r->head, 0u);
    atomic_init(&r->tail, 0u);
    atomic_init(&r->dropped, 0u);
}

bool can_ring_push(can_ring *r, const hal_can_frame *f)
{
    const uint32_t head = atomic_load_explicit(&r->head, memory_order_relaxed);
    /* Acquire: the consumer has finished reading every slot up to tail. */
    const uint32_t tail = atomic_load_explicit(&r->tail, memory_order_acquire);
    if (head - tail >= CAN_RING_CAPACITY) {
        /* Producer-only counter: a plain load and store, no read-modify-write needed. */
        const uint32_t d = atomic_load_explicit(&r->dropped, memory_order_relaxed);
        atomic_store_explicit(&r->dropped, d + 1u, memory_order_relaxed);
        return false;
    }
    r->slot[head & MASK] = *f;
    atomic_store_explicit(&r->head, head + 1u, memory_order_release);
    return true;
}

bool can_ring_pop(can_ring *r, hal_can_frame *f)
{
    const uint32_t tail = atomic_load_explicit(&r->tail, memory_order_relaxed);
    /* Acquire: the slot at tail was written before head moved past it. */
    const uint32_t head = atomic_load_explicit(&r->head, memory_order_acquire);
    if (head == tail)
        return false;
    *f = r->slot[tail & MASK];
    atomic_store_explicit(&r->tail, tail + 1u, memory_order_release);
    return true;
}

uint32_t can_ring_count(can_ring *r)
{
    const uint32_t tail = atomic_load_explicit(&r->tail, memory_order_acquire);
    const uint32_t head = atomic_load_explicit(&r->head, memory_order_acquire);
    const uint32_t n = head - tail; /* head read last: a third context may see it a bit ahead */
    return n < CAN_RING_CAPACITY ? n : CAN_RING_CAPACITY;
}

uint32_t can_ring_dropped(can_ring *r)
{
    return atomic_load_explicit(&r->dropped, memory_order_relaxed);
}
