/* Which of the plant's steps tse-sim reports as coming after an e-stop: those taken while it held,
 * from the control call that saw the e-stop to the one that saw the controller leave the e-stop
 * state (CLEAR_FAULT).  Steps after that are legitimate motion (enable, home, move again).
 *
 * Ticks are the plant's step counts (tse_plant.tick) as a control call sees them: the steps of
 * the step interrupts that follow a control call at tick t are at t, t + 1, ... (plant.h), so a
 * step at tick t came after everything that call did. */
#ifndef TSE_SIM_ESTOP_WATCH_H
#define TSE_SIM_ESTOP_WATCH_H

#include <stdbool.h>
#include <stdint.h>

/* Whether a step at pulse_tick came while the e-stop held: taken at taken_tick, cleared at
 * cleared_tick (UINT64_MAX while it still holds). */
bool estop_step_held(uint64_t taken_tick, uint64_t cleared_tick, uint64_t pulse_tick);

typedef struct {
    bool taken;            /* an e-stop was ever taken */
    uint64_t taken_tick;   /* the latest one */
    uint64_t cleared_tick; /* when it was cleared; UINT64_MAX while it holds */
    bool judged_any;       /* a step has been judged since the latest e-stop */
    uint64_t judged;       /* steps up to this tick have been judged (one report per step) */
} estop_watch;

void estop_watch_init(estop_watch *w);
/* The controller entered the e-stop state, seen by the control call at tick. */
void estop_watch_taken(estop_watch *w, uint64_t tick);
/* The controller left the e-stop state, seen by the control call at tick. */
void estop_watch_cleared(estop_watch *w, uint64_t tick);
/* The plant's latest step is at pulse_tick (call only once the plant has stepped at all): true
 * when it is a step not yet judged that came while an e-stop held, with *after its distance from
 * the e-stop in ticks. */
bool estop_watch_pulse(estop_watch *w, uint64_t pulse_tick, uint64_t *after);

#endif
