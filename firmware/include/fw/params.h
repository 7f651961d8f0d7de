/* The controller's parameters: one table (id, name, integer unit, range, default; written once, in
 * fw/params.def), the raw set the CAN protocol reads and writes, and its conversion into what
 * kinematics and planning use.
 *
 * A set is only ever replaced whole: a change is applied to a copy, checked (each value's range,
 * then the kinematic validity of the whole set), and only then adopted. */
#ifndef FW_PARAMS_H
#define FW_PARAMS_H

#include <stddef.h>
#include <stdint.h>

#include "tse/geometry.h"

typedef enum {
    FP_L = 0,         /* total scissor length [um] */
    FP_K1,            /* l0 / L [ppm] */
    FP_ETA,           /* slide angle [urad] */
    FP_K3,            /* r_act / L [ppm] */
    FP_K4,            /* r_top / L [ppm] */
    FP_ALPHA_MIN,     /* [urad] */
    FP_ALPHA_MAX,     /* [urad] */
    FP_S_MIN,         /* [um] */
    FP_S_MAX,         /* [um] */
    FP_MU_MIN,        /* [ppm] */
    FP_NU_MIN,        /* [ppm] */
    FP_STEPS_PER_M,   /* [steps/m] */
    FP_SLIDE_VMAX,    /* [um/s] */
    FP_SLIDE_AMAX,    /* [um/s^2] */
    FP_PLATE_VMAX,    /* [um/s] */
    FP_PLATE_AMAX,    /* [um/s^2] */
    FP_PLATE_JMAX,    /* [um/s^3] */
    FP_PLATE_WMAX,    /* [urad/s] */
    FP_PLATE_DWMAX,   /* [urad/s^2] */
    FP_STEP_RATE_MAX, /* [steps/s] per axis */
    FP_WATCHDOG_MS,   /* host heartbeat timeout [ms], 0 = off */
    FP_STATUS_MS,     /* STATUS period [ms] */
    FP_TELEMETRY_MS,  /* SLIDES/FK period [ms], 0 = off */
    FP_HOMING_SPEED,  /* [um/s] */
    FP_HOMING_BACKOFF,/* [um] */
    FP_HOME_SW_1,     /* [um] slide coordinate at which slide 1's homing switch trips */
    FP_HOME_SW_2,
    FP_HOME_SW_3,
    FP_HOME_SW_4,
    FP_HOME_SW_5,
    FP_HOME_SW_6,
    FP_STEP_PULSE_NS, /* [ns] STEP high time */
    FP_DIR_SETUP_NS,  /* [ns] DIR stable before a STEP edge */
    FP_CAN_KBPS,      /* [kbit/s] 125, 250, 500 or 1000; applied by the board at start-up */
    FP_TRAJ_LEAD,     /* [us] trajectory held before its clock starts */
    FP_NODE,          /* CAN node id 1..15; applied by the platform at start-up */
    FP_ENABLE_LEVEL,  /* fw_enable_level; applied by the board at start-up */
    FP_COUNT
} fw_param_id;

/* enable_level's values: the ENABLE output's active level (the board maps them at start-up). */
typedef enum {
    FW_ENABLE_LEVEL_BOARD = 0, /* the board's own, from its description */
    FW_ENABLE_LEVEL_HIGH = 1,  /* high = drivers enabled */
    FW_ENABLE_LEVEL_LOW = 2,   /* low = drivers enabled */
} fw_enable_level;

/* The controller's parameter that carries kinematic parameter id (TSE_PARAM_L ... TSE_PARAM_NU_MIN):
 * the table keeps the library's order from FP_L, under the library's names. */
static inline fw_param_id fw_param_of_kin(tse_param_id id)
{
    return (fw_param_id)(FP_L + (int)id - (int)TSE_PARAM_L);
}

/* Once homed, a low switch must be pressed below home_sw_k - this and released above
 * home_sw_k + this (controller.c).  0.5 mm: a mechanical or inductive switch's hysteresis and
 * repeatability (0.1 to 0.3 mm) plus the one-step latch and a step of read-out skew, 640 steps at
 * the default 1.28M steps/m; a stalled drive loses whole steps in groups of 256 (four full steps
 * at 1/64), so two or three stalls already show. */
#define FW_HOME_SW_TOLERANCE_UM 500

/* What the firmware needs of a parameter: its range and default, in its integer unit. */
typedef struct {
    int32_t min, max, def;
} fw_param_spec;

extern const fw_param_spec fw_param_specs[FP_COUNT];

/* The whole table, names, units and documentation with the numbers: the host's (tsectl, protogen,
 * the parameter files).  It lives in the library tse_fw_doc (firmware/doc/param_table.c), which
 * host programs get with the firmware's library and the board image does not link. */
typedef struct {
    const char *name;
    const char *unit; /* of the integer on the wire */
    int32_t min, max, def;
    const char *doc;
} fw_param_def;

extern const fw_param_def fw_param_table[FP_COUNT];

typedef struct {
    int32_t v[FP_COUNT];
} fw_param_set;

void fw_params_default(fw_param_set *s);

/* Kinematic parameters of a set (SI units). */
void fw_params_kinematics(const fw_param_set *s, tse_params *out);

/* The rules a parameter set can break, one code each: REJECT's `where` for a param_set refusal
 * (proto_param_rules in firmware/doc/proto_codes.c words each).  Wire values: append, never
 * renumber. */
typedef enum {
    FW_RULE_NONE = 0,           /* the set is valid (or, from an older controller: not said) */
    FW_RULE_RANGE = 1,          /* a value outside its range, or a can_kbps not one of the rates */
    FW_RULE_GEOMETRY = 2,       /* kinematics.md's valid sets, other than the two orders below */
    FW_RULE_ALPHA_ORDER = 3,    /* alpha_min < alpha_max */
    FW_RULE_STROKE_ORDER = 4,   /* s_min < s_max */
    FW_RULE_SWITCH_STROKE = 5,  /* each home_sw_k within s_min..s_max */
    FW_RULE_SWITCH_REACH = 6,   /* the six switches reachable together (fw_params_judge) */
    FW_RULE_PULSE_PERIOD = 7,   /* the STEP pulse ends within its step interrupt period */
    FW_RULE_PULSE_LOW = 8,      /* ... and leaves as long low before the same slide's next step */
    FW_RULE_DIR_SETUP_ROOM = 9, /* the DIR set-up leaves room for a step in a reversing segment */
    FW_RULE_CONFIG = 10,        /* the controller's step and segment rates cannot run any set */
    FW_RULE_NOT_AT_REST = 11,   /* the step generator was still running */
    FW_RULE_HOME_MARGINS = 12,  /* the home pose passes its own margins (mu_min, nu_min, stroke) */
    FW_RULE_HOMING_PATH = 13,   /* homing's final move from the switches stays at valid poses */
    FW_RULE_PLATE_STEP = 14,    /* a step at a ball joint turns the plate FW_PLATE_STEP_URAD at most */
    FW_RULE_COUNT
} fw_param_rule;

/* The most one step at a ball joint may turn the plate [urad]: r_top * steps_per_m >= 1e6 / this.
 * A plate of micrometres (k4 = 1 ppm is in its range) has an orientation no step count can hold or
 * report: its forward kinematics is lost in the steps' rounding. */
#define FW_PLATE_STEP_URAD 1000

/* Why a set is refused: the rule, and the parameter the check blames (-1 for none: the set is
 * valid, or the rule is not about one parameter). */
typedef struct {
    int id;
    fw_param_rule rule;
} fw_param_fault;

/* Checks every range (and can_kbps against its four rates), then the geometry, then that the six
 * homing switches can be reached together: with every slide at its switch each scissor must be
 * within its angle stops (its width at least 2 l0 cos alpha_max), otherwise six slides seeking
 * down together would be stopped by the mechanism before the switches; then that the home pose
 * passes its own margins and that homing's final move, straight in slide space from the switches
 * to the home pose's slides, passes valid poses only (fw/joint_path.h).  The first rule broken,
 * with the parameter at fault (a switch pair is blamed through its first switch); rule
 * FW_RULE_NONE and id -1 when all is well.  What depends on the controller's configuration (the
 * STEP pulse and DIR set-up against its step interrupt rate) is fw_params_judge_config's
 * (fw/limits.h). */
fw_param_fault fw_params_judge(const fw_param_set *s);

/* fw_params_judge's parameter: -1 when all is well, otherwise the id of the first parameter at
 * fault. */
int fw_params_check(const fw_param_set *s);

/* Applies one change to *s only if the resulting set passes fw_params_check.
 * Returns 0, FW_REASON_PARAM_UNKNOWN, FW_REASON_PARAM_RANGE (outside [min, max], or a can_kbps
 * that is not one of the four rates) or FW_REASON_PARAM_SET, with the rule broken in *why (may
 * be NULL).  What depends on the controller's configuration (the STEP pulse against the step
 * interrupt rate) is checked when the controller adopts the set (fw_apply_params). */
int fw_params_set_one(fw_param_set *s, uint16_t id, int32_t value, fw_param_fault *why);

/* Whether value is acceptable for parameter id on its own (range, and the CAN rates). */
int fw_param_value_ok(uint16_t id, int32_t value);

/* Storage record: a version tag, the number of parameters, the set, and a CRC-32.  serialize
 * returns the length written (or 0 if cap is too small); deserialize returns 0 for a good record,
 * -1 otherwise (and leaves *s untouched).  A good record may hold fewer parameters than this
 * firmware knows (an older firmware's: parameters are only appended); the rest take their
 * defaults. */
size_t fw_params_serialize(const fw_param_set *s, uint8_t *buf, size_t cap);
int fw_params_deserialize(fw_param_set *s, const uint8_t *buf, size_t len);

#endif
