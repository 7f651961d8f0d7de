#include "hal_fault/fault_time.h"

bool fault_window_empty(const fault_window *w)
{
    return w->until_us <= w->from_us;
}

bool fault_window_holds(const fault_window *w, uint64_t t_us)
{
    return !fault_window_empty(w) && t_us >= w->from_us && t_us < w->until_us;
}

void fault_clock_init(fault_clock *c, hal_clock clock)
{
    c->clock = clock;
    c->t0 = clock.now_us(clock.ctx);
}

uint64_t fault_clock_us(const fault_clock *c)
{
    return c->clock.now_us(c->clock.ctx) - c->t0;
}
