/* What the controller fuzz target reached, for its report: the states the controller was seen in
 * and the transitions between them, the answers by function and the reasons of the refusals, the
 * faults latched and the rig's operations.  Counting is a few increments; the table is printed at
 * exit only when the environment variable TSE_FUZZ_SUMMARY is set (e.g. over a corpus:
 * TSE_FUZZ_SUMMARY=1 fuzz_controller -runs=0 corpus/), so fuzzing does not pay for it. */
#ifndef FUZZ_CONTROLLER_SUMMARY_H
#define FUZZ_CONTROLLER_SUMMARY_H

#include <stdint.h>

#include "fw/types.h"

void summary_input(void);
void summary_state(fw_state from, fw_state to);
void summary_answer(uint8_t function, int rejected, fw_reason reason);
void summary_fault(fw_fault f);
void summary_op(unsigned op);
void summary_homed(void);

#endif
