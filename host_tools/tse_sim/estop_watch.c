/* tse-sim's judgement of steps against e-stops (estop_watch.h). */
#include "estop_watch.h"

bool estop_step_held(uint64_t taken_tick, uint64_t cleared_tick, uint64_t pulse_tick)
{
    return pulse_tick >= taken_tick && pulse_tick < cleared_tick;
}

void estop_watch_init(estop_watch *w)
{
    w->taken = false;
    w->taken_tick = 0;
    w->cleared_tick = UINT64_MAX;
    w->judged_any = false;
    w->judged = 0;
}

void estop_watch_taken(estop_watch *w, uint64_t tick)
{
    w->taken = true;
    w->taken_tick = tick;
    w->cleared_tick = UINT64_MAX;
    w->judged_any = false;
}

void estop_watch_cleared(estop_watch *w, uint64_t tick)
{
    if (w->taken && w->cleared_tick == UINT64_MAX)
        w->cleared_tick = tick;
}

bool estop_watch_pulse(estop_watch *w, uint64_t pulse_tick, uint64_t *after)
{
    /* A step already judged (the plant keeps reporting its latest one) is not news. */
    if (!w->taken || (w->judged_any && pulse_tick <= w->judged))
        return false;
    w->judged_any = true;
    w->judged = pulse_tick;
    if (!estop_step_held(w->taken_tick, w->cleared_tick, pulse_tick))
        return false;
    *after = pulse_tick - w->taken_tick;
    return true;
}
