/* When a fault holds: windows of time measured from the start of the layer that injects it, on
 * whatever hal_clock the platform gives (the fake clock of a test, the monotonic clock of
 * tse-sim). */
#ifndef HAL_FAULT_TIME_H
#define HAL_FAULT_TIME_H

#include <stdbool.h>
#include <stdint.h>

#include "hal/clock.h"

#define FAULT_FOREVER UINT64_MAX

/* [from_us, until_us) after the start; empty (never holds) when until_us <= from_us, so a zeroed
 * window is no fault.  until_us = FAULT_FOREVER: from from_us on. */
typedef struct {
    uint64_t from_us, until_us;
} fault_window;

bool fault_window_holds(const fault_window *w, uint64_t t_us);
bool fault_window_empty(const fault_window *w);

typedef struct {
    hal_clock clock;
    uint64_t t0;
} fault_clock;

/* Time starts now. */
void fault_clock_init(fault_clock *c, hal_clock clock);
/* Microseconds since fault_clock_init. */
uint64_t fault_clock_us(const fault_clock *c);

#endif
