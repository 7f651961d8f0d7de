/* What a parameter set means for a controller of a given configuration: its geometry, the motion
 * limits planning and validation hold every path to, and the step generator's timing.
 *
 * One derivation, shared by the controller (fw_apply_params adopts exactly these) and by host
 * tools that must judge a path with the very limits the controller will (tsectl checking a
 * trajectory file offline).  Pure functions: no controller, no hardware. */
#ifndef FW_LIMITS_H
#define FW_LIMITS_H

#include <stdbool.h>
#include <stdint.h>

#include "fw/move.h"
#include "fw/params.h"
#include "fw/stepgen.h"
#include "tse/geometry.h"

/* The configuration tse-fw (board/main.c) and tse-sim run by default: 200 kHz step interrupts and
 * 1 kHz control segments.  A controller reports the rates it runs in INFO; host tools judge a set
 * or a path at those, and at these built-in ones only offline or for a firmware older than INFO. */
#define FW_STEP_HZ 200000u
#define FW_SEGMENT_HZ 1000u

/* A controller's rates: step interrupts and control segments per second (fw_config's). */
typedef struct {
    uint32_t step_hz, segment_hz;
} fw_rates;
#define FW_RATES_BUILT_IN ((fw_rates){FW_STEP_HZ, FW_SEGMENT_HZ})

/* Whether a controller runs at rates r (fw_init refuses others): a control segment of whole
 * microseconds (trajectory time is kept in them) and of whole step interrupts, and both rates
 * within INFO's fields, which report them. */
bool fw_rates_run(fw_rates r);

/* Planned slide motion keeps this much of the step generator's capacity in hand: a segment's
 * steps are its setpoints rounded to whole steps, so a slide at the speed limit may ask one step
 * more than the speed gives, and the inverse kinematics' rounding (float on the board) a little
 * more; 10 % is that step at 10 or more steps a segment (10 kHz at 1 kHz segments) and leaves the
 * generator's ceiling, where a segment that asks more is an overrun, out of reach. */
#define FW_STEP_RATE_MARGIN TSE_R(0.9)

/* The ticks between two steps of one slide at step_rate_max `rate` (at least step_hz / rate,
 * rounded up, and at least 1), and the ticks of DIR set-up dir_ns asks for (rounded up, plus one
 * for the jitter of the writes within a step interrupt; 1 for none): what the step generator is
 * configured with. */
uint32_t fw_step_interval_ticks(int32_t rate, uint32_t step_hz);
uint32_t fw_dir_setup_ticks(uint32_t dir_ns, uint32_t step_hz);

/* The step generator's timing for parameter set s at step_hz step interrupts and segment_hz
 * control segments per second: the STEP pulse and DIR set-up in whole ticks, and the spacing the
 * step rate limit asks for.  Returns FW_RULE_NONE (0), or the rule s breaks: FW_RULE_CONFIG (the
 * configuration is unusable: segment_hz zero or not dividing step_hz), FW_RULE_PULSE_PERIOD,
 * FW_RULE_PULSE_LOW or FW_RULE_DIR_SETUP_ROOM (*sc is then unspecified). */
fw_param_rule fw_stepgen_config_from_params(const fw_param_set *s, uint32_t step_hz, uint32_t segment_hz,
                                            stepgen_config *sc);

/* Everything a controller of configuration (step_hz, segment_hz) asks of set s: fw_params_judge,
 * then the step generator's timing (the parameter blamed: step_pulse_ns for the pulse rules,
 * dir_setup_ns for the set-up's, none for the configuration's). */
fw_param_fault fw_params_judge_config(const fw_param_set *s, uint32_t step_hz, uint32_t segment_hz);

/* The slide speed limit in effect, with what sets it.  Planning and validation hold a slide to the
 * lower of slide_vmax and the step generator's limit: FW_STEP_RATE_MARGIN of the steps it can
 * emit in a control segment that changes direction (its ticks less the DIR set-up, one step per
 * step interval of at least 1 / step_rate_max), / steps_per_m.  That is always below
 * FW_STEP_RATE_MARGIN x step_rate_max / steps_per_m: the set-up takes at least a tick, and the
 * interval is step_hz / step_rate_max rounded up. */
typedef struct {
    tse_real vmax;          /* m/s: the lower of the two */
    fw_slide_limit by;      /* which: FW_LIMIT_SLIDE_VMAX or FW_LIMIT_STEP_GENERATOR */
    tse_real by_param;      /* slide_vmax [m/s] */
    tse_real by_steps;      /* the step generator's [m/s] */
    uint32_t segment_steps; /* the steps a segment that changes direction holds */
    stepgen_config sc;      /* the step generator's timing it comes from */
} fw_speed_limit;

/* The slide speed limit set s gives at (step_hz, segment_hz).  Returns 0, or -1 (*v unspecified)
 * when fw_stepgen_config_from_params refuses. */
int fw_speed_limit_from_params(const fw_param_set *s, uint32_t step_hz, uint32_t segment_hz, fw_speed_limit *v);

/* The geometry and motion limits a controller with configuration (step_hz, segment_hz) derives
 * from parameter set s: what fw_apply_params adopts.  Returns 0, or -1 when s is refused
 * (fw_params_judge_config finds a rule broken); *g and *lim are then left untouched. */
int fw_limits_from_params(const fw_param_set *s, uint32_t step_hz, uint32_t segment_hz,
                          tse_geometry *g, fw_limits *lim);

/* The slides' jerk limit [m/s^3]: the plate's jerk limit in the ratio of the two acceleration
 * limits, slide_amax x plate_jmax / plate_amax.  Homing's joint move keeps to it, and the path
 * planner's time laws. */
tse_real fw_slide_jmax(const fw_limits *lim);

#endif
