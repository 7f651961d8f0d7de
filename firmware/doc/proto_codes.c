/* The codes REJECT carries for one reason, with their words (fw/proto_table.h): the controller
 * sends the codes and never the words, which only the host's library (tse_fw_doc) carries. */
#include "fw/move.h"
#include "fw/params.h"
#include "fw/proto_table.h"

/* Noun phrases: "would need 1.35 times WORDS".  The step generator's 0.9 is FW_STEP_RATE_MARGIN
 * (fw/limits.h; test_limits.c holds the two equal). */
const proto_code proto_slide_limits[] = {
    {FW_LIMIT_SLIDE_VMAX, "slide_vmax", "its speed limit (slide_vmax)"},
    {FW_LIMIT_SLIDE_AMAX, "slide_amax", "its acceleration limit (slide_amax)"},
    {FW_LIMIT_STEP_GENERATOR, "step_generator",
     "its speed limit in effect, the step generator's, lower than slide_vmax: 0.9 x the steps that fit "
     "in a control segment that changes direction (after the DIR set-up, dir_setup_ns; one step per "
     "step interval, at most step_rate_max a second) / steps_per_m ('tsectl params get slide_vmax' shows "
     "it)"},
    {0, 0, 0},
};

/* Clauses: "rejected: param_set: NAME: WORDS; nothing was changed". */
const proto_code proto_param_rules[] = {
    {FW_RULE_NONE, "unspecified",
     "the value is in range but the whole set it gives is not valid (geometry, stroke, homing switches "
     "or step timing)"},
    {FW_RULE_RANGE, "range", "a value of the set is outside its range"},
    {FW_RULE_GEOMETRY, "geometry",
     "the geometry it gives breaks a rule of a valid parameter set (docs/kinematics.md)"},
    {FW_RULE_ALPHA_ORDER, "alpha_order", "alpha_min must be below alpha_max"},
    {FW_RULE_STROKE_ORDER, "stroke_order", "s_min must be below s_max"},
    {FW_RULE_SWITCH_STROKE, "switch_stroke",
     "every homing switch (home_sw_1..6) must be within the stroke s_min..s_max"},
    {FW_RULE_SWITCH_REACH, "switch_reach",
     "the six homing switches must be reachable together: with both slides of a scissor at their "
     "switches the scissor must be at least 2 l0 cos(alpha_max) wide, or its alpha_max stop halts "
     "them first"},
    {FW_RULE_PULSE_PERIOD, "pulse_period",
     "the STEP pulse (step_pulse_ns) must end within one step interrupt period of the controller"},
    {FW_RULE_PULSE_LOW, "pulse_low",
     "the STEP pulse (step_pulse_ns) must leave a low time at least as long as itself before the same "
     "slide's next step, one step interval (1 / step_rate_max, in whole step interrupts) later"},
    {FW_RULE_DIR_SETUP_ROOM, "dir_setup_room",
     "the DIR set-up (dir_setup_ns, in whole step interrupts, plus one) must leave room for a step in a "
     "control segment that changes direction"},
    {FW_RULE_CONFIG, "config",
     "the controller's step interrupt and control segment rates cannot run any set (a firmware "
     "configuration fault)"},
    {FW_RULE_NOT_AT_REST, "not_at_rest",
     "the step generator was still running: parameters change only at rest (try again)"},
    {FW_RULE_HOME_MARGINS, "home_margins",
     "the home pose must pass its own margins (mu_min, nu_min) and stroke, or every move from it is "
     "refused"},
    {FW_RULE_HOMING_PATH, "homing_path",
     "homing's final move, straight in slide space from the homing switches (home_sw_1..6) to the home "
     "pose, must pass valid poses only (within the workspace and both margins)"},
    {FW_RULE_PLATE_STEP, "plate_step",
     "the top plate (r_top = k4 x L) must be wide enough that one step at a ball joint turns it by at "
     "most 1 mrad: k4 x L x steps_per_m at least 1000"},
    {0, 0, 0},
};

const proto_code_def proto_code_tables[] = {
    {proto_slide_limits, "slide_limit", "slide limit (`REJECT` timing: `field` / 16)"},
    {proto_param_rules, "param_rule", "param_set rule (`REJECT` param_set: `where`)"},
    {0, 0, 0},
};
