/* Measures how close a sequence of slide setpoints comes to the slide speed and acceleration
 * limits.  Fed one setpoint per control segment, as execution will produce them; the slides are
 * taken to be at rest before the first setpoint, and fw_slide_check_finish adds the stop after
 * the last.
 *
 * Acceleration is the second difference over FW_ACC_STRIDE segments,
 * (q_k - 2 q_{k-S} + q_{k-2S}) / (S T)^2, at every segment: the simulator's plant measures it the
 * same way, so what planning allows is what the plant accepts.  A shorter stride would measure the
 * rounding of the inverse kinematics (1e-7 m in float over (1 ms)^2 is 0.1 m/s^2) and the step
 * quantisation. */
#ifndef FW_SLIDE_CHECK_H
#define FW_SLIDE_CHECK_H

#include <stdbool.h>
#include <stdint.h>

#include "tse/real.h"

#define FW_ACC_STRIDE 10u

typedef struct {
    tse_real vmax, amax;  /* limits, m/s and m/s^2 */
    tse_real segment_hz;
    tse_real q[6];        /* latest setpoint */
    tse_real hist[2 * FW_ACC_STRIDE][6]; /* the last 2S setpoints (the start, before any) */
    uint32_t n;           /* setpoints fed */
    tse_real v_ratio;     /* worst |v| / vmax so far */
    tse_real a_ratio;     /* worst |a| / amax so far */
    uint8_t v_slide;      /* the slide (q index 0..5) that set v_ratio */
    uint8_t a_slide;      /* the slide that set a_ratio */
} fw_slide_check;

/* The worse of the two ratios, and where it came from: what a timing refusal names. */
typedef struct {
    uint8_t slide;        /* q index 0..5 (A1, B1, A2, B2, A3, B3) */
    bool accel;           /* the acceleration limit, not the speed limit */
    tse_real ratio;       /* demand / limit */
} fw_slide_worst;

void fw_slide_check_start(fw_slide_check *c, tse_real vmax, tse_real amax, tse_real segment_hz,
                          const tse_real q_start[6]);

/* The next setpoint, dt seconds after the previous one. */
void fw_slide_check_feed(fw_slide_check *c, const tse_real q[6], tse_real dt);

/* The slides come to rest after the last setpoint. */
void fw_slide_check_finish(fw_slide_check *c);

/* Whether no ratio so far is over its limit (above 1). */
bool fw_slide_check_ok(const fw_slide_check *c);

/* The larger of the speed and acceleration ratios so far (speed on a tie), and its slide. */
fw_slide_worst fw_slide_check_worst(const fw_slide_check *c);

#endif
