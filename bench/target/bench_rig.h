/* The controller on an in-RAM HAL for the board's instruction counts (target_bench.c) and the search
 * for its costliest frames (frame_search.c): no bus, no plant, a clock the caller advances.  QEMU
 * with -icount shift=0 makes TIM2 at prescaler 0 gain one count per guest instruction. */
#ifndef BENCH_RIG_H
#define BENCH_RIG_H

#include <stdbool.h>
#include <stdint.h>

#include "fw/controller.h"
#include "fw/proto.h"

extern fw_controller *bench_ctl;
extern uint64_t bench_now_us;
extern uint32_t bench_overhead; /* what two reads of the counter back to back differ by */

/* Starts TIM2 counting instructions; returns bench_overhead, which a measurement subtracts. */
uint32_t bench_counter_start(void);
static inline uint32_t bench_count(void)
{
    return *(volatile uint32_t *)0x40000024u; /* TIM2->CNT */
}
/* Clears TIM2's overflow flag; bench_wrapped() says whether the counter wrapped since (a call of
 * 2^32 instructions or more: 25 s at 168 MHz). */
void bench_wrap_clear(void);
bool bench_wrapped(void);

/* The controller with the default parameters, enabled, homed at the home pose without running the
 * homing sequence (a benchmark shortcut: it needs switches).  0, or -1 if it did not start. */
int bench_rig_start(void);
/* The controller at rest at pose p, its slides there (p must be reachable): 0, else -1. */
int bench_rig_place(const tse_real p[6]);

/* Queues a frame for the controller's next poll (fw_poll); bench_frame queues it and polls. */
void bench_queue(proto_msg msg, const int32_t *v);
void bench_frame(proto_msg msg, const int32_t *v);
void bench_stage(uint8_t seq, const tse_real pose[6]);
/* A control period with the host alive, as the board's contexts order it on one context
 * (fw/runtime.h): a heartbeat polled, the control tick (its instructions into *c when c is not
 * NULL), the period's step ticks. */
void bench_period(uint32_t *c);

/* One adversarial commit: from rest at `from`, a MOVE_COMMIT to `to` of kind 0 (duration, ms) or 1
 * (speed, um/s) and that value. */
typedef struct {
    tse_real from[6], to[6];
    int32_t kind, value;
} bench_commit;

/* Instructions the poll that takes the commit's MOVE_COMMIT costs (fw_poll, the frame waiting), with its answer ('a' ACK, 'r'
 * REJECT) and, for a REJECT, its reason; the controller is put back at rest afterwards.  UINT32_MAX
 * for a frame that wrapped the counter, 0 when `from` is not reachable.  *hold (when not NULL):
 * the poll's longest stretch between two reads of the bus (bench_hold_end). */
uint32_t bench_commit_cost(const bench_commit *bc, char *answer, int *reason, uint32_t *hold);

/* Around a call of the thread's: the longest it went without reading the bus (from the begin to
 * its first read, between two reads, from its last read to the end), in instructions: how long
 * the board is held from the bus, deaf to a STOP and silent (docs/validation.md).  Meanwhile the
 * controller's clock runs with the instructions at 168 MHz, as on the board. */
void bench_hold_begin(void);
uint32_t bench_hold_end(void);

#endif
