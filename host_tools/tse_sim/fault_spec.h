/* tse-sim --fault SPEC: which faults the fault layer (hal/fault) injects between the firmware
 * and hal/posix, as comma-separated items (fault_spec_help lists them):
 *   drop=0.01,dup=0.01,reorder=0.01,delay=0.01,corrupt=0.01,delay_ms=20,seed=7,
 *   silence=5+2,busoff=8+0.1,estop=12,limit=3@4+0.5,stall=2@6
 * Times are seconds after tse-sim starts; T+D holds from T for D, T alone from T on. */
#ifndef TSE_SIM_FAULT_SPEC_H
#define TSE_SIM_FAULT_SPEC_H

#include <stddef.h>

#include "hal_fault/fault_can.h"
#include "hal_fault/fault_inputs.h"
#include "hal_fault/fault_stepper.h"

typedef struct {
    fault_can_config can;
    fault_inputs_config inputs;
    fault_stepper_config stepper;
} fault_plan;

/* The --help lines for --fault, each ending in a newline. */
extern const char fault_spec_help[];

/* Fills *plan from spec (every fault absent unless given; seed 1 and delay_ms 20 unless given).
 * Returns 0, or -1 with err saying which item is wrong and why (*plan then undefined). */
int fault_spec_parse(const char *spec, fault_plan *plan, char *err, size_t errlen);

#endif
