/* Bresenham interpolation of six axes between segment setpoints.
 *
 * Within a segment of span ticks an axis that must make delta steps makes step j at the first
 * tick t with 2 delta t + span >= (2j) span, i.e. in the middle of each of the delta equal parts
 * of the segment: the emitted position never strays more than half a step from the straight line
 * between setpoints, and with delta <= span / interval two steps are at least interval ticks apart,
 * also across segment boundaries (half a part at the end of one, half at the start of the next). */
#include "fw/stepgen.h"

#include <string.h>

static uint32_t abs_diff(int32_t to, int32_t from, bool *forward)
{
    const int64_t d = (int64_t)to - (int64_t)from;
    *forward = d > 0;
    const int64_t m = d < 0 ? -d : d;
    return m > (int64_t)UINT32_MAX ? UINT32_MAX : (uint32_t)m;
}

uint32_t stepgen_capacity(const stepgen_config *cfg, bool direction_change)
{
    const uint32_t span = cfg->ticks_per_segment - (direction_change ? cfg->dir_setup_ticks : 0u);
    return span / cfg->min_step_interval;
}

int stepgen_init(stepgen *sg, const stepgen_config *cfg, const int32_t position[STEPGEN_AXES])
{
    if (cfg->ticks_per_segment == 0 || cfg->min_step_interval == 0 || cfg->dir_setup_ticks == 0 ||
        cfg->dir_setup_ticks >= cfg->ticks_per_segment ||
        cfg->ticks_per_segment > UINT32_MAX / 4u)
        return -1;
    memset(sg, 0, sizeof *sg);
    sg->cfg = *cfg;
    atomic_init(&sg->head, 0u);
    atomic_init(&sg->tail, 0u);
    atomic_init(&sg->halted, false);
    for (int i = 0; i < STEPGEN_AXES; ++i) {
        sg->ax[i].position = position[i];
        sg->ax[i].forward = true;
    }
    sg->forward_mask = (uint8_t)((1u << STEPGEN_AXES) - 1u);
    return 0;
}

int stepgen_push(stepgen *sg, const int32_t target[STEPGEN_AXES])
{
    const unsigned head = atomic_load_explicit(&sg->head, memory_order_relaxed);
    const unsigned tail = atomic_load_explicit(&sg->tail, memory_order_acquire);
    if (head - tail >= STEPGEN_QUEUE)
        return -1;
    memcpy(sg->queue[head % STEPGEN_QUEUE], target, sizeof sg->queue[0]);
    atomic_store_explicit(&sg->head, head + 1u, memory_order_release);
    return 0;
}

unsigned stepgen_queued(const stepgen *sg)
{
    stepgen *m = (stepgen *)sg; /* atomic loads need a non-const object in C11 */
    return atomic_load_explicit(&m->head, memory_order_acquire) -
           atomic_load_explicit(&m->tail, memory_order_acquire);
}

static bool pop(stepgen *sg, int32_t target[STEPGEN_AXES])
{
    const unsigned tail = atomic_load_explicit(&sg->tail, memory_order_relaxed);
    const unsigned head = atomic_load_explicit(&sg->head, memory_order_acquire);
    if (head == tail)
        return false;
    memcpy(target, sg->queue[tail % STEPGEN_QUEUE], sizeof sg->queue[0]);
    atomic_store_explicit(&sg->tail, tail + 1u, memory_order_release);
    return true;
}

static void begin_segment(stepgen *sg, const int32_t target[STEPGEN_AXES])
{
    const stepgen_config *cfg = &sg->cfg;
    bool overrun = false;
    uint8_t mask = 0;
    for (int i = 0; i < STEPGEN_AXES; ++i) {
        stepgen_axis *a = &sg->ax[i];
        bool forward;
        /* From the emitted position, so that anything an earlier overrun left over is made up. */
        uint32_t delta = abs_diff(target[i], a->position, &forward);
        if (delta == 0)
            forward = a->forward; /* an axis at rest keeps its direction pin */
        const bool change = forward != a->forward;
        const uint32_t cap = stepgen_capacity(cfg, change);
        if (delta > cap) {
            delta = cap;
            overrun = true;
        }
        a->forward = forward;
        a->start = a->position;
        a->delta = delta;
        a->done = 0;
        a->first = change ? cfg->dir_setup_ticks + 1u : 1u;
        a->span = cfg->ticks_per_segment - (a->first - 1u);
        a->acc = a->span;
        if (forward)
            mask |= (uint8_t)(1u << i);
    }
    if (overrun)
        ++sg->overruns;
    sg->forward_mask = mask;
    sg->tick = 0;
    sg->running = true;
}

stepgen_output stepgen_tick(stepgen *sg)
{
    stepgen_output out = {0, sg->forward_mask, false};
    /* A byte load: on the one core, the e-stop interrupt's store is seen by the next tick. */
    if (atomic_load_explicit(&sg->halted, memory_order_relaxed))
        return out;
    if (!sg->running) {
        int32_t target[STEPGEN_AXES];
        if (!pop(sg, target))
            return out;
        const uint8_t before = sg->forward_mask;
        begin_segment(sg, target);
        out.forward_mask = sg->forward_mask;
        out.dir_changed = sg->forward_mask != before;
    }
    const uint32_t t = ++sg->tick;
    for (int i = 0; i < STEPGEN_AXES; ++i) {
        stepgen_axis *a = &sg->ax[i];
        if (t < a->first || a->done >= a->delta)
            continue;
        a->acc += 2u * a->delta;
        if (a->acc >= 2u * a->span) {
            a->acc -= 2u * a->span;
            ++a->done;
            a->position += a->forward ? 1 : -1;
            out.step_mask |= (uint8_t)(1u << i);
        }
    }
    if (t >= sg->cfg.ticks_per_segment)
        sg->running = false;
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

void stepgen_abort(stepgen *sg)
{
    stepgen_halt(sg);
    /* The halt before any change, as the step interrupt on this core would see them. */
    atomic_signal_fence(memory_order_seq_cst);
    sg->running = false;
    atomic_store_explicit(&sg->tail, atomic_load_explicit(&sg->head, memory_order_acquire),
                          memory_order_release);
    /* The queue is empty and no segment runs: nothing to step when the ticks resume. */
    atomic_store(&sg->halted, false);
}

int stepgen_set_position(stepgen *sg, const int32_t position[STEPGEN_AXES])
{
    if (!stepgen_idle(sg))
        return -1;
    for (int i = 0; i < STEPGEN_AXES; ++i)
        sg->ax[i].position = position[i];
    return 0;
}

void stepgen_positions(const stepgen *sg, int32_t out[STEPGEN_AXES])
{
    for (int i = 0; i < STEPGEN_AXES; ++i)
        out[i] = sg->ax[i].position;
}
