/* Bresenham interpolation of six axes between segment setpoints.
 *
 * Within a segment of span ticks an axis that must make delta steps makes step j at the first
 * tick t with 2 delta t + span >= (2j) span, i.e. in the middle of each of the delta equal parts
 * of the segment: the emitted position never strays more than half a step from the straight line
 * between setpoints, and with delta <= span / interval two steps are at least interval ticks apart,
 * also across segment boundaries (half a part at the end of one, half at the start of the next).
 *
 * Counted from the axis' first tick, after t ticks it has made floor((span + 2 delta t) / (2 span))
 * steps: delta after its span ticks, whatever the tick.  That is what the interrupt's error term
 * does one tick at a time (acc = span + 2 delta t - 2 span steps stays in [0, 2 span) since
 * delta <= span), and what stepgen_positions computes from the tick count.
 *
 * Work is placed where it costs least: stepgen_push (the control loop) prepares a segment
 * completely, because the emitted position at its start is known in advance (every segment
 * reaches its clipped delta exactly), and the interrupt runs it in its slot of the ring.  It runs
 * the same update on every axis, moving or not (no test of which axes move: a test costs what it
 * would save), until one of two ticks it was told about: the end of a direction set-up (the held
 * axes get their increment) and the end of the segment. */
#include "fw/stepgen.h"

#include <string.h>

_Static_assert(STEPGEN_RING >= STEPGEN_QUEUE + 1 && (STEPGEN_RING & (STEPGEN_RING - 1)) == 0,
               "the ring holds the running segment besides the waiting ones, and wraps with the "
               "free-running indices");

uint32_t stepgen_capacity(const stepgen_config *cfg, bool direction_change)
{
    const uint32_t span = cfg->ticks_per_segment - (direction_change ? cfg->dir_setup_ticks : 0u);
    return span / cfg->min_step_interval;
}

/* Nothing runs and nothing waits (the caller has emptied the queue): the axes at rest at
 * position, as if a segment without steps had ended there, in the slot just before the next one
 * the producer fills. */
static void rest_at(stepgen *sg, const int32_t position[STEPGEN_AXES])
{
    const uint32_t ticks = sg->cfg.ticks_per_segment;
    const unsigned cur = (atomic_load_explicit(&sg->head, memory_order_relaxed) - 1u) % STEPGEN_RING;
    stepgen_segment *s = &sg->ring[cur];
    for (int i = 0; i < STEPGEN_AXES; ++i) {
        s->ax[i].err = -(int32_t)ticks;
        s->ax[i].inc = 0;
        s->ax[i].dec = 2u * ticks;
        s->start[i] = position[i];
        s->delta[i] = 0;
        sg->planned[i] = position[i];
    }
    s->event = ticks;
    s->forward_mask = sg->forward_mask;
    s->held_mask = 0;
    s->overrun = false;
    sg->cur = cur;
    sg->tick = ticks;
    sg->event = ticks;
    sg->running = false;
    sg->planned_forward = sg->forward_mask;
}

int stepgen_init(stepgen *sg, const stepgen_config *cfg, const int32_t position[STEPGEN_AXES])
{
    /* ticks_per_segment <= UINT32_MAX / 4 keeps 2 span + 2 delta within int32_t. */
    if (cfg->ticks_per_segment == 0 || cfg->min_step_interval == 0 || cfg->dir_setup_ticks == 0 ||
        cfg->dir_setup_ticks >= cfg->ticks_per_segment ||
        cfg->ticks_per_segment > UINT32_MAX / 4u)
        return -1;
    memset(sg, 0, sizeof *sg);
    sg->cfg = *cfg;
    atomic_init(&sg->seq, 0u);
    atomic_init(&sg->head, 0u);
    atomic_init(&sg->tail, 0u);
    atomic_init(&sg->halted, false);
    sg->forward_mask = (uint8_t)((1u << STEPGEN_AXES) - 1u);
    rest_at(sg, position);
    return 0;
}

/* The segment from where the queued ones leave the axes to target. */
static void prepare(stepgen *sg, stepgen_segment *s, const int32_t target[STEPGEN_AXES])
{
    const stepgen_config *cfg = &sg->cfg;
    /* Indexed by whether the axis changes direction: a held axis spreads its steps over the ticks
     * after its set-up. */
    const uint32_t span_of[2] = {cfg->ticks_per_segment, cfg->ticks_per_segment - cfg->dir_setup_ticks};
    const uint32_t cap_of[2] = {stepgen_capacity(cfg, false), stepgen_capacity(cfg, true)};
    const uint32_t was = sg->planned_forward;
    bool overrun = false;
    uint32_t mask = 0, held = 0;
    for (int i = 0; i < STEPGEN_AXES; ++i) {
        /* From where the axis will be, so that anything an earlier overrun left over is made up. */
        const int32_t from = sg->planned[i];
        const int64_t d = (int64_t)target[i] - from;
        const uint32_t was_forward = (was >> i) & 1u;
        /* an axis at rest keeps its direction pin */
        const uint32_t forward = d > 0 ? 1u : d < 0 ? 0u : was_forward;
        const uint32_t change = forward ^ was_forward;
        const uint64_t need = (uint64_t)(d < 0 ? -d : d);
        uint32_t delta = cap_of[change];
        if (need <= delta)
            delta = (uint32_t)need;
        else
            overrun = true;
        const uint32_t span = span_of[change];
        s->ax[i].err = -(int32_t)span;
        s->ax[i].inc = change ? 0u : 2u * delta;
        s->ax[i].dec = 2u * span;
        s->start[i] = from;
        s->delta[i] = delta;
        sg->planned[i] = forward ? from + (int32_t)delta : from - (int32_t)delta;
        mask |= forward << i;
        held |= change << i;
    }
    s->overrun = overrun;
    sg->planned_forward = (uint8_t)mask;
    s->forward_mask = (uint8_t)mask;
    s->held_mask = (uint8_t)held;
    s->event = held ? cfg->dir_setup_ticks : cfg->ticks_per_segment;
}

int stepgen_push(stepgen *sg, const int32_t target[STEPGEN_AXES])
{
    const unsigned head = atomic_load_explicit(&sg->head, memory_order_relaxed);
    const unsigned tail = atomic_load_explicit(&sg->tail, memory_order_acquire);
    if (head - tail >= STEPGEN_QUEUE)
        return -1;
    /* Never the running segment's slot, (tail - 1) % STEPGEN_RING: head - (tail - 1) is 1 to
     * STEPGEN_QUEUE, less than the ring. */
    prepare(sg, &sg->ring[head % STEPGEN_RING], target);
    atomic_store_explicit(&sg->head, head + 1u, memory_order_release);
    return 0;
}

unsigned stepgen_queued(const stepgen *sg)
{
    stepgen *m = (stepgen *)sg; /* atomic loads need a non-const object in C11 */
    return atomic_load_explicit(&m->head, memory_order_acquire) -
           atomic_load_explicit(&m->tail, memory_order_acquire);
}

/* The next prepared segment becomes the running one; false when none is queued.  Out of line, so
 * that the common tick keeps its registers. */
static __attribute__((noinline)) bool start_segment(stepgen *sg)
{
    const unsigned tail = atomic_load_explicit(&sg->tail, memory_order_relaxed);
    const unsigned head = atomic_load_explicit(&sg->head, memory_order_acquire);
    if (head == tail)
        return false;
    const unsigned cur = tail % STEPGEN_RING;
    /* stepgen_positions retries when seq changed or is odd: it never mixes two segments. */
    const unsigned seq = atomic_load_explicit(&sg->seq, memory_order_relaxed);
    atomic_store_explicit(&sg->seq, seq + 1u, memory_order_relaxed);
    atomic_thread_fence(memory_order_release);
    sg->cur = cur;
    sg->forward_mask = sg->ring[cur].forward_mask;
    sg->event = sg->ring[cur].event;
    sg->tick = 0;
    sg->running = true;
    atomic_store_explicit(&sg->seq, seq + 2u, memory_order_release);
    if (sg->ring[cur].overrun)
        ++sg->overruns;
    /* The slot is the running segment's from now on: see stepgen_push. */
    atomic_store_explicit(&sg->tail, tail + 1u, memory_order_release);
    return true;
}

/* Off the common path: the tick the segment named in sg->event. */
static __attribute__((noinline)) void segment_event(stepgen *sg, uint32_t t)
{
    if (t >= sg->cfg.ticks_per_segment) {
        sg->running = false;
        return;
    }
    /* The direction set-up is over: the held axes step from the next tick on, from the error
     * term they were given (-span), as if their segment began now. */
    stepgen_segment *s = &sg->ring[sg->cur];
    for (int i = 0; i < STEPGEN_AXES; ++i)
        s->ax[i].inc = 2u * s->delta[i]; /* what the others have had from the start */
    sg->event = sg->cfg.ticks_per_segment;
}

stepgen_output stepgen_tick(stepgen *sg)
{
    stepgen_output out = {0, sg->forward_mask, false};
    /* A byte load: on the one core, the e-stop interrupt's store is seen by the next tick. */
    if (atomic_load_explicit(&sg->halted, memory_order_relaxed))
        return out;
    if (!sg->running) {
        if (!start_segment(sg))
            return out;
        out.dir_changed = sg->forward_mask != out.forward_mask;
        out.forward_mask = sg->forward_mask;
    }
    const uint32_t t = ++sg->tick;
    stepgen_axis *ax = sg->ring[sg->cur].ax;
    uint32_t mask = 0;
    /* Per axis an add, a sign test and on a step a subtraction and a bit: the compiler makes the
     * test a conditional execution or a short forward branch (a mask computed without a test
     * cost more instructions here), and the loop straight-line code. */
    for (int i = 0; i < STEPGEN_AXES; ++i) {
        int32_t e = ax[i].err + (int32_t)ax[i].inc;
        if (e >= 0) {
            e -= (int32_t)ax[i].dec;
            mask |= 1u << i;
        }
        ax[i].err = e;
    }
    out.step_mask = (uint8_t)mask;
    if (t == sg->event)
        segment_event(sg, t);
    return out;
}

bool stepgen_idle(const stepgen *sg)
{
    return !sg->running && stepgen_queued(sg) == 0;
}

void stepgen_halt(stepgen *sg)
{
    atomic_store(&sg->halted, true);
}

/* Steps an axis has made t ticks into a segment: none before its first tick (1, or
 * dir_setup_ticks + 1 when held), then floor((span + 2 delta n) / (2 span)) after n of its span
 * ticks.  In 32 bits when that fits (spans up to 32767 ticks). */
static uint32_t steps_made(const stepgen_config *cfg, uint32_t delta, bool held, uint32_t t)
{
    const uint32_t skip = held ? cfg->dir_setup_ticks : 0u;
    if (t <= skip)
        return 0;
    const uint32_t span = cfg->ticks_per_segment - skip, n = t - skip;
    if (span <= 32767u)
        return (span + 2u * delta * n) / (2u * span);
    return (uint32_t)(((uint64_t)span + 2u * (uint64_t)delta * n) / (2u * (uint64_t)span));
}

void stepgen_positions(const stepgen *sg, int32_t out[STEPGEN_AXES])
{
    stepgen *m = (stepgen *)sg; /* atomic loads need a non-const object in C11 */
    for (;;) {
        const unsigned seq = atomic_load_explicit(&m->seq, memory_order_acquire);
        /* One read of each: every axis at the same instant. */
        const uint32_t t = *(const volatile uint32_t *)&sg->tick;
        const uint32_t cur = *(const volatile uint32_t *)&sg->cur;
        const stepgen_segment *s = &sg->ring[cur % STEPGEN_RING];
        for (int i = 0; i < STEPGEN_AXES; ++i) {
            const int32_t made = (int32_t)steps_made(&sg->cfg, s->delta[i], (s->held_mask >> i) & 1u, t);
            out[i] = s->start[i] + (((s->forward_mask >> i) & 1u) ? made : -made);
        }
        atomic_thread_fence(memory_order_acquire);
        if (!(seq & 1u) && atomic_load_explicit(&m->seq, memory_order_relaxed) == seq)
            return;
    }
}

void stepgen_abort(stepgen *sg)
{
    stepgen_halt(sg);
    /* The halt before any change, as the step interrupt on this core would see them. */
    atomic_signal_fence(memory_order_seq_cst);
    int32_t pos[STEPGEN_AXES];
    stepgen_positions(sg, pos);
    atomic_store_explicit(&sg->tail, atomic_load_explicit(&sg->head, memory_order_acquire),
                          memory_order_release);
    rest_at(sg, pos);
    /* The queue is empty and no segment runs: nothing to step when the ticks resume. */
    atomic_store(&sg->halted, false);
}

int stepgen_set_position(stepgen *sg, const int32_t position[STEPGEN_AXES])
{
    if (!stepgen_idle(sg))
        return -1;
    rest_at(sg, position);
    return 0;
}
