/* The adversarial MOVE_COMMITs over which target_bench measures frame_worst (frame_cases.c). */
#ifndef FRAME_CASES_H
#define FRAME_CASES_H

#include "bench_rig.h"

extern const bench_commit bench_frame_cases[];
extern const unsigned bench_frame_case_count;

#endif
