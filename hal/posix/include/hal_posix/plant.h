/* The simulator's plant: six slides that integrate the step pulses they receive, switches, an
 * e-stop input, and the plate pose from forward kinematics.  It implements hal_stepper and
 * hal_inputs.  Slide k's low (homing) switch is pressed for s <= home_sw[k] and released above it
 * (a reference the slides pass in legitimate poses, not an end of travel); its high switch is
 * pressed for s > s_max.  It checks on every step what a real robot needs (reported, never
 * silently absorbed):
 *   - never beyond the mechanical stroke (the kinematic stroke plus an overtravel at each end);
 *   - no step while the drives are disabled; steps of one axis at least min_interval ticks apart;
 *   - the drivers' timing, in time (the tick is 1 / step_hz) from what hal_stepper.timing last
 *     programmed: a STEP edge at least dir_setup_ns after its axis' DIR changed, DIR never
 *     changed while its STEP is still high (pulse_ns after the edge), and two STEP edges of one
 *     axis at least twice pulse_ns apart (high, then as long low);
 *   - slide speed, from the spacing of consecutive steps, within the limit (one tick of jitter
 *     allowed); slide acceleration, the second difference of the position over 10 ms taken every
 *     millisecond (the planner's measure), within the limit (two steps of quantisation allowed),
 *     judged only while the drives are on (an e-stop stops dead by design). */
#ifndef HAL_POSIX_PLANT_H
#define HAL_POSIX_PLANT_H

#include <stdatomic.h>
#include <stdbool.h>
#include <stdint.h>

#include "hal/inputs.h"
#include "hal/stepper.h"
#include "tse/params.h"

#define PLANT_OVERTRAVEL 0.010 /* m beyond each end of the kinematic stroke */

typedef enum {
    PLANT_OK = 0,
    PLANT_BEYOND_STROKE = 1u << 0,
    PLANT_STEP_DISABLED = 1u << 1,
    PLANT_PULSE_SPACING = 1u << 2,
    PLANT_DIR_SETUP = 1u << 3,
    PLANT_OVERSPEED = 1u << 4,
    PLANT_OVERACCEL = 1u << 5,
} plant_breach;

typedef struct {
    double steps_per_m;
    double vmax, amax;        /* slide limits [m/s, m/s^2] */
    double tolerance;         /* relative margin on vmax, amax */
    uint32_t step_hz;         /* step interrupt rate (the plant's clock) */
    uint32_t min_interval;    /* ticks */
    uint32_t pulse_ns;        /* drivers' timing at power-up (hal_stepper.timing reprograms it) */
    uint32_t dir_setup_ns;
    double home_sw[6];        /* where each low switch trips [m] */
} plant_config;

/* The machine's kinematic parameters [m, rad]: the plant is the world, computed in double
 * whatever precision the controller beside it is built in (tests/sim runs the controller in
 * float too, as the board computes). */
typedef struct {
    double L, k1, eta, k3, k4, alpha_min, alpha_max, s_min, s_max, mu_min, nu_min;
} plant_kinematics;

/* From the kinematics' parameters in the includer's precision (a float controller's are within
 * 1e-7 of their decimal values: the machine is then built as the board believes it). */
static inline plant_kinematics plant_kinematics_of(const tse_params *p)
{
    const plant_kinematics k = {(double)p->L,         (double)p->k1,        (double)p->eta,
                                (double)p->k3,        (double)p->k4,        (double)p->alpha_min,
                                (double)p->alpha_max, (double)p->s_min,     (double)p->s_max,
                                (double)p->mu_min,    (double)p->nu_min};
    return k;
}

/* The double-precision geometry, held as bytes so that this header means one layout in a TU of
 * either precision (tse_geometry's depends on it); only plant.c reads it. */
#define PLANT_GEOMETRY_BYTES 512
typedef struct {
    _Alignas(8) unsigned char bytes[PLANT_GEOMETRY_BYTES];
} plant_geometry;

typedef struct {
    plant_config cfg;
    plant_geometry geom;
    int64_t steps[6];         /* true slide positions, steps from s = 0 */
    uint8_t forward;
    atomic_bool enabled; /* the drives: off also from the controller's thread (an ESTOP frame) */
    bool estop_open;
    uint64_t tick;            /* step interrupts so far */
    uint64_t last_step[6];    /* tick of each axis' latest step (0: none) */
    uint64_t dir_change[6];   /* tick of each axis' latest direction change */
    uint8_t dir_changed;      /* axes whose direction has changed at least once */
    uint8_t stepped;          /* axes that have stepped at least once */
    int64_t sw_steps[6];      /* last step position at which each low switch is pressed */
    uint32_t pulse_ns, dir_setup_ns; /* as last programmed */
    uint32_t timing_calls;    /* hal_stepper.timing calls so far */
    int64_t hist[20][6];      /* positions at the last 20 millisecond boundaries */
    uint32_t ms;              /* millisecond boundaries passed */
    uint32_t quiet_ms;        /* acceleration not judged (drives off, or just back on) */
    uint32_t breaches;        /* plant_breach bits seen so far */
    char first_breach[160];   /* what and where, for the log */
    uint64_t pulses;
    uint64_t last_pulse_tick; /* tick of the latest step of any axis */
    uint64_t mark_tick;       /* plant_mark(): the tick marked */
    uint64_t first_after_mark;/* tick of the first step since the mark (0: none yet) */
    double pose[6];           /* plate pose from forward kinematics */
    bool pose_valid;
} tse_plant;

/* Slides start at `start` [m] (where the robot was at power-up).  Returns 0, or -1 when the
 * kinematics refuses the parameters (the plant is then unusable). */
int plant_init(tse_plant *p, const plant_config *cfg, const plant_kinematics *k, const double start[6]);

hal_stepper plant_stepper(tse_plant *p);
hal_inputs plant_inputs(tse_plant *p);

/* Advances the plant's clock by one step interrupt (call once per step tick, after it). */
void plant_tick(tse_plant *p);

/* Marks the current tick; p->first_after_mark then records the first step after it (latency). */
void plant_mark(tse_plant *p);

/* True slide positions [m]. */
void plant_slides(const tse_plant *p, double s[6]);

/* Updates p->pose by forward kinematics from the true slides, seeded with the last pose. */
bool plant_update_pose(tse_plant *p);

#endif
