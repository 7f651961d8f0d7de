/* A single-producer single-consumer ring of CAN frames, lock-free: one context (an interrupt, or
 * thread code) pushes while another pops, without masking interrupts.
 *
 * Promises: frames come out once each, in the order pushed; push never blocks and, when the ring
 * is full, drops the new frame and counts it; no heap (the storage is in the struct).
 * Exactly one producer and one consumer at a time: a second context on either side needs its
 * own exclusion.
 *
 * How: head and tail are free-running 32-bit counters (their difference is the fill, correct
 * across wrap-around because the capacity divides 2^32).  Only the producer writes head and
 * `dropped`, only the consumer writes tail.  The producer fills a slot, then publishes it with a
 * release store of head; the consumer acquires head before reading the slot, and releases tail
 * only after copying it out, so the producer never overwrites a slot still being read. */
#ifndef TSE_CAN_RING_H
#define TSE_CAN_RING_H

#include <stdatomic.h>
#include <stdbool.h>
#include <stdint.h>

#include "hal/can.h"

/* A power of two.  The bootloader's image builds its CAN driver with more (boot/stm32f4): a
 * window of blocks arrives while it programs one. */
#ifndef CAN_RING_CAPACITY
#define CAN_RING_CAPACITY 32u
#endif
_Static_assert((CAN_RING_CAPACITY & (CAN_RING_CAPACITY - 1u)) == 0, "ring capacity: power of two");

typedef struct {
    _Atomic uint32_t head;    /* frames pushed (producer) */
    _Atomic uint32_t tail;    /* frames popped (consumer) */
    _Atomic uint32_t dropped; /* frames refused because the ring was full (producer) */
    hal_can_frame slot[CAN_RING_CAPACITY];
} can_ring;

/* Empties the ring and zeroes the drop count.  Not concurrent with push or pop. */
void can_ring_init(can_ring *r);

/* Producer: appends *f.  Returns false (and counts a drop) when the ring is full. */
bool can_ring_push(can_ring *r, const hal_can_frame *f);

/* Consumer: takes the oldest frame into *f.  Returns false when the ring is empty. */
bool can_ring_pop(can_ring *r, hal_can_frame *f);

/* Frames waiting (exact from the producer or the consumer while the other side is idle; a
 * snapshot otherwise). */
uint32_t can_ring_count(can_ring *r);

uint32_t can_ring_dropped(can_ring *r);

#endif
