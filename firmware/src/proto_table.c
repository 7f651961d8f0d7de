/* The protocol, declared once.  See fw/proto_table.h. */
#include "fw/proto_table.h"

#include "fw/doc.h"
#include "fw/types.h"
#include "tse/status.h"

const proto_enum_entry proto_state_names[] = {
    {FW_STATE_BOOT, "boot"},         {FW_STATE_DISABLED, "disabled"}, {FW_STATE_HOMING, "homing"},
    {FW_STATE_IDLE, "idle"},         {FW_STATE_MOVING, "moving"},     {FW_STATE_STOPPING, "stopping"},
    {FW_STATE_FAULT, "fault"},       {FW_STATE_ESTOP, "estop"},       {0, 0},
};

const proto_enum_entry proto_fault_names[] = {
    {FW_FAULT_NONE, "none"},
    {FW_FAULT_WATCHDOG, "watchdog"},
    {FW_FAULT_LIMIT, "limit"},
    {FW_FAULT_BUS_OFF, "bus_off"},
    {FW_FAULT_PLANNER, "planner"},
    {FW_FAULT_STEP_OVERRUN, "step_overrun"},
    {FW_FAULT_HOMING, "homing"},
    {FW_FAULT_ESTOP, "estop"},
    {FW_FAULT_UNDERRUN, "underrun"},
    {FW_FAULT_PLANT, "plant"},
    {FW_FAULT_HARDWARE, "hardware"},
    {0, 0},
};

const proto_enum_entry proto_reason_names[] = {
    {FW_REASON_NONE, "none"},
    {FW_REASON_BAD_LENGTH, "bad_length"},
    {FW_REASON_UNKNOWN, "unknown"},
    {FW_REASON_RANGE, "range"},
    {FW_REASON_STATE, "state"},
    {FW_REASON_NOT_HOMED, "not_homed"},
    {FW_REASON_INCOMPLETE, "incomplete"},
    {FW_REASON_STALE, "stale"},
    {FW_REASON_KINEMATICS, "kinematics"},
    {FW_REASON_QUEUE_FULL, "queue_full"},
    {FW_REASON_PARAM_UNKNOWN, "param_unknown"},
    {FW_REASON_PARAM_RANGE, "param_range"},
    {FW_REASON_PARAM_SET, "param_set"},
    {FW_REASON_STORAGE, "storage"},
    {FW_REASON_TIMING, "timing"},
    {FW_REASON_ORDER, "order"},
    {FW_REASON_ENDED, "ended"},
    {FW_REASON_TOO_LONG, "too_long"},
    {0, 0},
};

const proto_enum_entry proto_kin_status_names[] = {
    {TSE_OK, "ok"},           {TSE_INVALID, "invalid"},   {TSE_UNREACHABLE, "unreachable"},
    {TSE_BELOW, "below"},     {TSE_ALPHA, "alpha"},       {TSE_STROKE, "stroke"},
    {TSE_SINGULAR, "singular"}, {TSE_DEGENERATE, "degenerate"}, {TSE_NOCONVERGE, "noconverge"},
    {0, 0},
};

const proto_enum_entry proto_move_kind_names[] = {
    {0, "duration"},
    {1, "speed"},
    {0, 0},
};

const proto_enum_entry proto_move_start_names[] = {
    {FW_START_REST, "rest"},
    {FW_START_BLENDED, "blended"},
    {FW_START_AFTER, "after"},
    {0, 0},
};

const proto_enum_entry proto_move_bound_names[] = {
    {FW_BOUND_ASKED, "asked"},
    {FW_BOUND_PLATE_VMAX, "plate_vmax"},
    {FW_BOUND_PLATE_AMAX, "plate_amax"},
    {FW_BOUND_PLATE_JMAX, "plate_jmax"},
    {FW_BOUND_PLATE_WMAX, "plate_wmax"},
    {FW_BOUND_PLATE_DWMAX, "plate_dwmax"},
    {FW_BOUND_PLATE_JMAX_ANGULAR, "plate_jmax_angular"},
    {FW_BOUND_SLIDE_VMAX, "slide_vmax"},
    {FW_BOUND_SLIDE_AMAX, "slide_amax"},
    {FW_BOUND_STEP_GENERATOR, "step_generator"},
    {0, 0},
};

const proto_enum_entry proto_traj_end_names[] = {
    {FW_TRAJ_END_NONE, "none"},
    {FW_TRAJ_END_DONE, "done"},
    {FW_TRAJ_END_STOP, "stop"},
    {FW_TRAJ_END_FAULT, "fault"},
    {0, 0},
};

const proto_flag proto_status_flags[] = {
    {PROTO_STATUS_HOMED, "homed", FW_DOC("homed")},
    {PROTO_STATUS_DRIVES, "drives", FW_DOC("drives enabled")},
    {PROTO_STATUS_ESTOP_IN, "estop_in", FW_DOC("e-stop input open")},
    {PROTO_STATUS_SWITCHES_OFF, "switches_off",
     FW_DOC("a high-end switch pressed or (once homed) a homing switch disagreeing with the step count")},
    {PROTO_STATUS_ERROR_PASSIVE, "error_passive", FW_DOC("CAN error passive")},
    {0, 0, 0},
};

const proto_flag proto_traj_flags[] = {
    {PROTO_TRAJ_LAST, "last", FW_DOC("the trajectory's last row")},
    {PROTO_TRAJ_FIRST, "first", FW_DOC("its first row, which starts it")},
    {0, 0, 0},
};

const proto_flag_field proto_flag_fields[] = {
    {PM_STATUS, 2, proto_status_flags},
    {PM_TRAJ_COMMIT, 2, proto_traj_flags},
    {PM_COUNT, 0, 0},
};

const proto_flag *proto_field_flags(proto_msg m, int k)
{
    for (const proto_flag_field *f = proto_flag_fields; f->flags; ++f)
        if (f->msg == m && f->field == k)
            return f->flags;
    return 0;
}

const proto_enum_def proto_enums[] = {
    {proto_state_names, "state", "state"},
    {proto_fault_names, "fault", "fault"},
    {proto_reason_names, "reason", "reject reason"},
    {proto_kin_status_names, "kin_status", "kinematic status (kinematics.md)"},
    {proto_move_kind_names, "move_kind", "move kind"},
    {proto_move_start_names, "move_start", "move start"},
    {proto_move_bound_names, "move_bound", "move bound"},
    {proto_traj_end_names, "traj_end", "trajectory end (`TRAJ_END.ended`, `REJECT` `ended`)"},
    {0, 0, 0},
};

/* Field shorthands: name, type, byte offset, raw range, unit, scale, value names, doc. */
#define SEQ(off) {"seq", PF_U8, off, 0, 255, "", 1.0, 0, FW_DOC("sequence number, echoed in ACK/REJECT")}
#define POS24(nm, off, doc) {nm, PF_I24, off, -PROTO_POS_MAX_UM, PROTO_POS_MAX_UM, "m", 1.0 / PROTO_UM_PER_M, 0, FW_DOC(doc)}
#define ANG24(nm, off, doc) {nm, PF_I24, off, -PROTO_ANGLE_MAX_URAD, PROTO_ANGLE_MAX_URAD, "rad", 1.0 / PROTO_URAD_PER_RAD, 0, FW_DOC(doc)}
#define FULL_I32(nm, off, unit, scale, doc) {nm, PF_I32, off, INT32_MIN, INT32_MAX, unit, scale, 0, FW_DOC(doc)}

const proto_def proto_table[PM_COUNT] = {
    {PM_ESTOP, 0x01, "ESTOP", PROTO_TO_CONTROLLER, 1, 1, {SEQ(0)},
     FW_DOC("Emergency stop: stepping is cut at once and the controller latches an e-stop fault. Node 0 "
     "stops every controller on the bus.")},
    {PM_STOP, 0x02, "STOP", PROTO_TO_CONTROLLER, 1, 1, {SEQ(0)},
     FW_DOC("Controlled stop: the running motion decelerates along its path within the limits and the "
     "trajectory queue is dropped: once at rest the queue is empty, and no further point of the "
     "stopped trajectory is accepted. Node 0 stops every controller.")},
    {PM_REJECT, 0x03, "REJECT", PROTO_TO_HOST, 8, 7,
     {{"function", PF_U8, 0, 0, 127, "", 1.0, 0, FW_DOC("function code of the refused message")},
      {"seq", PF_U8, 1, 0, 255, "", 1.0, 0, FW_DOC("its sequence number (0 when it had none)")},
      {"reason", PF_U8, 2, 0, FW_REASON_COUNT - 1, "", 1.0, proto_reason_names, FW_DOC("why")},
      {"scissor", PF_U8, 3, 0, 3, "", 1.0, 0,
       FW_DOC("for kinematics, the first failing scissor (1..3); for timing, the scissor (1..3) of the slide "
       "over its limit; for too_long with field 1, the scissor near whose limit the proof stopped; 0 "
       "otherwise")},
      {"kin_status", PF_U8, 4, 0, TSE_STATUS_COUNT - 1, "", 1.0, proto_kin_status_names,
       FW_DOC("for kinematics, the kinematic status of the first failing point; for too_long with field 1, "
       "the limit the proof could not show the path clear of; 0 otherwise")},
      {"field", PF_U8, 5, 0, 255, "", 1.0, 0,
       FW_DOC("for range, the index of the offending field (0 = its first, counting in byte order); for "
       "param_unknown, param_range and param_set, the parameter id (255 for an id above 255); for "
       "state, the controller's state when it refused (a state value as in STATUS); for timing, the "
       "slide over its limit, 1..6 for A1, B1, A2, B2, A3, B3, plus " PROTO_STR(PROTO_REJECT_LIMIT_STRIDE) " times the limit it is against "
       "(slide limit codes: 0 slide_vmax, 1 slide_amax, the acceleration, 2 the step generator's speed "
       "limit, when lower than slide_vmax); for too_long, 0 for a move that would last longer than a "
       "move may (its speed too slow, or its duration too long once stretched to the slide limits), 1 "
       "for a move too long to prove within one frame where its path comes near a limit of the "
       "workspace (scissor and kin_status name the limit)")},
      {"where", PF_U16, 6, 0, 65535, "per mille", 1.0, 0,
       FW_DOC("for kinematics, the position of the first failing point along the path (0..1000); for "
       "timing, the demand against the limit field names, per mille of that limit as in effect "
       "(1000 = at the limit, 1350 = 35 % over; capped at 65535); for param_set, the rule the set "
       "breaks (param_set rule codes; 0 from a controller that does not say); for too_long, with "
       "field 0 the longest a move may last in s (3600), with field 1 the position along the path "
       "(0..1000) where the proof stopped")}},
     FW_DOC("Every refused command gets one. Nothing of a refused command is applied. For order, field is the "
     "sequence number the running trajectory expects next. For ended, field is how the row's trajectory "
     "ended (a traj_end value: 0 none, no such trajectory ran; 1 done; 2 stop; 3 fault) plus 16 times "
     "the fault that ended it (as in STATUS), and where is how long before this row came it ended, in "
     "ms (capped at 65535): for an underrun, how late the host was with the row the controller lacked.")},
    {PM_ACK, 0x04, "ACK", PROTO_TO_HOST, 8, 5,
     {{"function", PF_U8, 0, 0, 127, "", 1.0, 0, FW_DOC("function code of the accepted message")},
      {"seq", PF_U8, 1, 0, 255, "", 1.0, 0, FW_DOC("its sequence number")},
      {"queue_depth", PF_U8, 2, 0, 255, "", 1.0, 0, FW_DOC("trajectory points waiting")},
      {"queue_free", PF_U8, 3, 0, 255, "", 1.0, 0, FW_DOC("trajectory points that may still be sent")},
      {"detail", PF_U32, 4, 0, INT32_MAX, "s", 1.0 / PROTO_MS_PER_S, 0,
       FW_DOC("for a move: its planned duration (after any stretching to the slide limits)")}},
     FW_DOC("Every accepted command gets one; it is also the flow control of trajectory streaming.")},
    {PM_HOST_HEARTBEAT, 0x05, "HOST_HEARTBEAT", PROTO_TO_CONTROLLER, 1, 1,
     {{"counter", PF_U8, 0, 0, 255, "", 1.0, 0, FW_DOC("free-running")}},
     FW_DOC("The host is alive. Silence past the watchdog timeout stops the robot and latches a fault "
     "(only while enabled).")},
    {PM_ENABLE, 0x06, "ENABLE", PROTO_TO_CONTROLLER, 1, 1, {SEQ(0)}, FW_DOC("Energise the drives.")},
    {PM_DISABLE, 0x07, "DISABLE", PROTO_TO_CONTROLLER, 1, 1, {SEQ(0)},
     FW_DOC("De-energise the drives (only at rest). The slides keep their zero.")},
    {PM_HOME, 0x08, "HOME", PROTO_TO_CONTROLLER, 1, 1, {SEQ(0)},
     FW_DOC("Find each slide's homing switch (pressed at and below home_sw_k, released above: a reference "
     "the slides pass in legitimate poses, not an end of travel): a slide that starts on it first "
     "moves up off it by homing_backoff; each seeks down at homing_speed to the press, brakes, and "
     "creeps up to the release edge, where its coordinate is set. Then all six go to the home pose. "
     "Once homed, a switch that disagrees with the step count by more than 0.5 mm latches a limit "
     "fault.")},
    {PM_CLEAR_FAULT, 0x09, "CLEAR_FAULT", PROTO_TO_CONTROLLER, 1, 1, {SEQ(0)},
     FW_DOC("Leave the fault or e-stop state (the e-stop input must be closed; an e-stop that latched "
            "after the controller took the command stays). The drives stay off.")},
    {PM_POSE_A, 0x0A, "POSE_A", PROTO_TO_CONTROLLER, 7, 3,
     {SEQ(0), POS24("x", 1, "plate centre X"), POS24("y", 4, "plate centre Y")},
     FW_DOC("Pose part 1 of 3, staged under its sequence number.")},
    {PM_POSE_B, 0x0B, "POSE_B", PROTO_TO_CONTROLLER, 7, 3,
     {SEQ(0), POS24("z", 1, "plate centre Z"), ANG24("roll", 4, "roll (about X, applied first)")},
     FW_DOC("Pose part 2 of 3.")},
    {PM_POSE_C, 0x0C, "POSE_C", PROTO_TO_CONTROLLER, 7, 3,
     {SEQ(0), ANG24("pitch", 1, "pitch (about Y)"), ANG24("yaw", 4, "yaw (about Z, applied last)")},
     FW_DOC("Pose part 3 of 3.")},
    {PM_MOVE_COMMIT, 0x0D, "MOVE_COMMIT", PROTO_TO_CONTROLLER, 6, 3,
     {SEQ(0),
      {"kind", PF_U8, 1, 0, 1, "", 1.0, proto_move_kind_names, FW_DOC("what value gives")},
      {"value", PF_U32, 2, 1, PROTO_MOVE_VALUE_MAX, "ms or um/s", 1.0, 0,
       FW_DOC("for kind duration, the move's duration in ms; for kind speed, the plate's speed in um/s")}},
     FW_DOC("Move to the staged pose of this sequence number, straight in position with the orientation "
     "interpolated. Applied only if all three parts of this sequence arrived and it is newer than "
     "the last accepted; the whole path is validated before the first step.")},
    {PM_TRAJ_COMMIT, 0x0E, "TRAJ_COMMIT", PROTO_TO_CONTROLLER, 7, 4,
     {SEQ(0),
      {"dt", PF_U32, 1, PROTO_DT_MIN_US, PROTO_DT_MAX_US, "s", 1.0 / PROTO_US_PER_S, 0,
       FW_DOC("time from the previous row (the first row: from the trajectory's start)")},
      {"flags", PF_U8, 5, 0, 3, "", 1.0, 0, FW_DOC("the row's place in its trajectory")},
      {"traj", PF_U8, 6, 0, 255, "", 1.0, 0,
       FW_DOC("the trajectory's identity: its first row's sequence number (the first row carries its own)")}},
     FW_DOC("Queue the staged pose of this sequence number as a row of a timed trajectory. A trajectory starts "
     "with a row flagged first, taken only while idle; every later row carries its identity and the "
     "sequence number after its previous row's (else order, nothing taken: a host with several rows in "
     "flight sends again from the first refused one). Its clock starts, with the plate at rest until "
     "then, once the controller holds traj_lead of it, its last row, or a full queue; a row of a "
     "trajectory that has ended is refused ended, whatever the state, and never starts another. See "
     "Streaming a trajectory, above.")},
    {PM_PARAM_GET, 0x0F, "PARAM_GET", PROTO_TO_CONTROLLER, 2, 1,
     {{"param", PF_U16, 0, 0, 65535, "", 1.0, 0, FW_DOC("parameter id")}}, FW_DOC("Read a parameter.")},
    {PM_PARAM_SET, 0x10, "PARAM_SET", PROTO_TO_CONTROLLER, 6, 2,
     {{"param", PF_U16, 0, 0, 65535, "", 1.0, 0, FW_DOC("parameter id")},
      FULL_I32("value", 2, "", 1.0, "new value, in the parameter's integer unit")},
     FW_DOC("Set a parameter (only while disabled or in fault); range-checked, then checked with the "
     "whole set; a refused value changes nothing. A change of what a step means or of the "
     "geometry (steps_per_m, home_sw_1..6, L, k1, eta, k3, k4, alpha_min, alpha_max, s_min, "
     "s_max) clears homed: home again before moving; the margins and limits keep it.")},
    {PM_PARAM_SAVE, 0x11, "PARAM_SAVE", PROTO_TO_CONTROLLER, 4, 1,
     {{"magic", PF_U32, 0, 0x45564153, 0x45564153, "", 1.0, 0,
       FW_DOC("0x45564153, the ASCII bytes S, A, V, E in wire order")}},
     FW_DOC("Store the parameter set in non-volatile memory.")},
    {PM_INFO_GET, 0x12, "INFO_GET", PROTO_TO_CONTROLLER, 1, 1,
     {{"page", PF_U8, 0, 0, 0, "", 1.0, 0,
       FW_DOC("what to report: 0, the firmware's version and the controller's rates (INFO); other pages are "
              "kept for later answers (a board's identity) and refused range until a firmware has them")}},
     FW_DOC("Ask what the controller is: acknowledged, then answered by the page's message (page 0: INFO). "
            "Accepted in every state; changes nothing.")},
    {PM_STATUS, 0x20, "STATUS", PROTO_TO_HOST, 8, 7,
     {{"state", PF_U8, 0, 0, FW_STATE_COUNT - 1, "", 1.0, proto_state_names, FW_DOC("controller state")},
      {"fault", PF_U8, 1, 0, FW_FAULT_COUNT - 1, "", 1.0, proto_fault_names, FW_DOC("latched fault")},
      {"flags", PF_U8, 2, 0, 255, "", 1.0, 0, FW_DOC("bits")},
      {"queue_depth", PF_U8, 3, 0, 255, "", 1.0, 0, FW_DOC("trajectory points waiting")},
      {"queue_free", PF_U8, 4, 0, 255, "", 1.0, 0, FW_DOC("trajectory points that may still be sent")},
      {"last_seq", PF_U8, 5, 0, 255, "", 1.0, 0, FW_DOC("last accepted sequence number")},
      {"counter", PF_U16, 6, 0, 65535, "", 1.0, 0, FW_DOC("free-running")}},
     FW_DOC("Heartbeat of the controller, every status period.")},
    {PM_SLIDES_A, 0x21, "SLIDES_A", PROTO_TO_HOST, 8, 2,
     {FULL_I32("s_a1", 0, "m", 1.0 / PROTO_NM_PER_M, "slide A1"), FULL_I32("s_b1", 4, "m", 1.0 / PROTO_NM_PER_M, "slide B1")},
     FW_DOC("Commanded slide positions (the steps emitted), every telemetry period. A slide beyond "
     "2.147483647 m (the stroke may reach 5 m) is sent as the field's end.")},
    {PM_SLIDES_B, 0x22, "SLIDES_B", PROTO_TO_HOST, 8, 2,
     {FULL_I32("s_a2", 0, "m", 1.0 / PROTO_NM_PER_M, "slide A2"), FULL_I32("s_b2", 4, "m", 1.0 / PROTO_NM_PER_M, "slide B2")},
     FW_DOC("Slides of scissor 2.")},
    {PM_SLIDES_C, 0x23, "SLIDES_C", PROTO_TO_HOST, 8, 2,
     {FULL_I32("s_a3", 0, "m", 1.0 / PROTO_NM_PER_M, "slide A3"), FULL_I32("s_b3", 4, "m", 1.0 / PROTO_NM_PER_M, "slide B3")},
     FW_DOC("Slides of scissor 3.")},
    {PM_FK_A, 0x24, "FK_A", PROTO_TO_HOST, 8, 2,
     {FULL_I32("x", 0, "m", 1.0 / PROTO_UM_PER_M, "plate X"), FULL_I32("y", 4, "m", 1.0 / PROTO_UM_PER_M, "plate Y")},
     FW_DOC("Plate pose from the forward kinematics of the slide positions, every telemetry period.")},
    {PM_FK_B, 0x25, "FK_B", PROTO_TO_HOST, 8, 2,
     {FULL_I32("z", 0, "m", 1.0 / PROTO_UM_PER_M, "plate Z"), FULL_I32("roll", 4, "rad", 1.0 / PROTO_URAD_PER_RAD, "roll")},
     FW_DOC("Pose part 2.")},
    {PM_FK_C, 0x26, "FK_C", PROTO_TO_HOST, 8, 2,
     {FULL_I32("pitch", 0, "rad", 1.0 / PROTO_URAD_PER_RAD, "pitch"), FULL_I32("yaw", 4, "rad", 1.0 / PROTO_URAD_PER_RAD, "yaw")},
     FW_DOC("Pose part 3.")},
    {PM_PARAM_VALUE, 0x27, "PARAM_VALUE", PROTO_TO_HOST, 6, 2,
     {{"param", PF_U16, 0, 0, 65535, "", 1.0, 0, FW_DOC("parameter id")},
      FULL_I32("value", 2, "", 1.0, "value in the parameter's integer unit")},
     FW_DOC("Answer to PARAM_GET and PARAM_SET.")},
    {PM_MOVE_INFO, 0x2A, "MOVE_INFO", PROTO_TO_HOST, 6, 5,
     {{"seq", PF_U8, 0, 0, 255, "", 1.0, 0, FW_DOC("the accepted MOVE_COMMIT's sequence number")},
      {"start", PF_U8, 1, 0, FW_START_COUNT - 1, "", 1.0, proto_move_start_names,
       FW_DOC("how it starts: from rest, blended into the running move's deceleration, or after it (back to "
       "back, where a blend would break a limit)")},
      {"bound", PF_U8, 2, 0, FW_BOUND_COUNT - 1, "", 1.0, proto_move_bound_names,
       FW_DOC("what set its pace: the duration or speed asked, a plate limit, or a slide limit that stretched "
       "it (slide_vmax also where the step rate is the lower limit)")},
      {"slide", PF_U8, 3, 0, 6, "", 1.0, 0,
       FW_DOC("for slide_vmax and slide_amax, the slide 1..6 (A1, B1, A2, B2, A3, B3); 0 otherwise")},
      {"demand", PF_U16, 4, 0, 65535, "per mille", 1.0, 0,
       FW_DOC("for slide_vmax and slide_amax, what that slide would have needed without the stretch (at the "
       "pace asked, or the plate limits' where slower), per mille of its limit (1140 = 14 % over; "
       "capped at 65535); 0 otherwise")}},
     FW_DOC("Sent right after the ACK of an accepted MOVE_COMMIT (whose detail is the planned duration): "
     "how the move starts and what set its pace.")},
    {PM_TRAJ_END, 0x28, "TRAJ_END", PROTO_TO_HOST, 6, 4,
     {{"traj", PF_U8, 0, 0, 255, "", 1.0, 0, FW_DOC("the trajectory's identity (its first row's sequence number)")},
      {"ended", PF_U8, 1, 1, FW_TRAJ_END_COUNT - 1, "", 1.0, proto_traj_end_names, FW_DOC("how it ended")},
      {"fault", PF_U8, 2, 0, FW_FAULT_COUNT - 1, "", 1.0, proto_fault_names,
       FW_DOC("for fault, the fault that ended it (underrun: the host fell behind; estop; ...); none otherwise")},
      {"rows", PF_U24, 3, 0, 16777215, "", 1.0, 0,
       FW_DOC("rows it took (capped); after an underrun, the row it lacked is the next one")}},
     FW_DOC("Sent once when a trajectory ends: when it ran to its last row (at rest), or the moment a STOP, a "
     "fault or an e-stop ends it (the robot then stops along the path).")},
    {PM_INFO, 0x29, "INFO", PROTO_TO_HOST, 8, 5,
     {{"major", PF_U8, 0, 0, 255, "", 1.0, 0, FW_DOC("the firmware's major version")},
      {"minor", PF_U8, 1, 0, 255, "", 1.0, 0, FW_DOC("its minor version")},
      {"patch", PF_U8, 2, 0, 255, "", 1.0, 0, FW_DOC("its patch version")},
      {"step_hz", PF_U24, 3, 1, 16777215, "Hz", 1.0, 0, FW_DOC("the step interrupts per second it runs")},
      {"segment_hz", PF_U16, 6, 1, 65535, "Hz", 1.0, 0,
       FW_DOC("the control segments per second it runs (a trajectory's rows and a move are judged over them)")}},
     FW_DOC("Answer to INFO_GET page 0, after its ACK: what the controller runs, so that a host judges a path "
            "or a parameter set at the controller's own rates (the slide speed its step generator allows, the "
            "segments a slide's acceleration is measured over) rather than assumed ones.")},
};
