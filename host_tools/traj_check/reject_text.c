#include "reject_text.h"

#include <stdio.h>
#include <string.h>

#include "boot/image.h"
#include "fw/params.h"
#include "fw/path.h"
#include "fw/reject.h"

const char *reject_slide_name(int slide)
{
    static const char *const names[6] = {"A1", "B1", "A2", "B2", "A3", "B3"};
    return slide >= 1 && slide <= 6 ? names[slide - 1] : "?";
}

static const char *command_name(int function)
{
    const proto_def *d = proto_lookup((uint8_t)function, PROTO_TO_CONTROLLER);
    return d ? d->name : "?";
}

/* What to do when a command meets a state that does not take it. */
static const char *state_advice(int function, int state)
{
    const proto_def *d = proto_lookup((uint8_t)function, PROTO_TO_CONTROLLER);
    const proto_msg m = d ? d->msg : PM_COUNT;
    if (state == FW_STATE_FAULT || state == FW_STATE_ESTOP) {
        if (m == PM_CLEAR_FAULT)
            return "the e-stop input is open: close it, then clear";
        return "clear it first ('tsectl clear'), then enable and home";
    }
    switch (m) {
    case PM_BOOT_ENTER:
        return "the drives may be on: stop and disable them first ('tsectl disable')";
    case PM_BOOT_QUERY:
    case PM_BOOT_ERASE:
    case PM_BOOT_WRITE:
    case PM_BOOT_VERIFY:
    case PM_BOOT_START:
    case PM_BOOT_DATA:
        return state == FW_STATE_BOOT ? "the bootloader takes it only in its turn of an update (ERASE first, "
                                        "'tsectl flash' sends them in order)"
                                      : "it is a bootloader's command: an application asks BOOT_ENTER first "
                                        "('tsectl flash' does)";
    case PM_HOME:
        if (state == FW_STATE_HOMING)
            return "homing is already running: wait for it ('tsectl home --wait' waits)";
        if (state == FW_STATE_DISABLED)
            return "enable the drives first ('tsectl enable')";
        return "wait until the motion ends, or stop it ('tsectl stop')";
    case PM_ENABLE:
        return state == FW_STATE_DISABLED ? "try again" : "the drives are already enabled";
    case PM_DISABLE:
        return "stop the motion first ('tsectl stop'), then disable";
    case PM_CLEAR_FAULT:
        return "there is no fault to clear";
    case PM_MOVE_COMMIT:
    case PM_TRAJ_COMMIT:
        if (state == FW_STATE_DISABLED)
            return "enable and home first ('tsectl enable', 'tsectl home --wait')";
        if (state == FW_STATE_HOMING)
            return "wait for homing to end ('tsectl home --wait')";
        if (state == FW_STATE_STOPPING)
            return "the controller is bringing the robot to rest (a STOP, a fault or the host falling "
                   "behind ended the motion): wait until it is idle, then start again";
        return "another motion is running or stopping: wait for it to end, or stop it "
               "('tsectl stop'); this controller does not queue a move behind a running one";
    case PM_PARAM_SET:
    case PM_PARAM_SAVE:
        return "parameters change only while disabled or in fault: stop, then 'tsectl disable'";
    default:
        return "see 'tsectl --help' for what each state accepts";
    }
}

/* A row of a trajectory that has ended: how it ended (a traj_end and the fault) and how long
 * before the row came (ms, 65535 for that or more). */
static void ended_text(char *buf, size_t cap, const char *cmd, int how, int fault, int ms)
{
    char ago[48];
    if (ms >= 65535)
        snprintf(ago, sizeof ago, "65.5 s or more");
    else
        snprintf(ago, sizeof ago, "%d ms", ms);
    if (how == FW_TRAJ_END_DONE)
        snprintf(buf, cap, "rejected: ended: %s: its trajectory had run to its last row %s before this row came", cmd,
                 ago);
    else if (how == FW_TRAJ_END_STOP)
        snprintf(buf, cap,
                 "rejected: ended: %s: its trajectory was ended by a STOP %s before this row came; nothing more of "
                 "it is taken",
                 cmd, ago);
    else if (how == FW_TRAJ_END_FAULT && fault == FW_FAULT_UNDERRUN)
        snprintf(buf, cap,
                 "rejected: ended: %s: this row came %s late: the controller had run out of path (underrun) and "
                 "stopped the robot; the host must keep the queue ahead (stream faster, or raise traj_lead)",
                 cmd, ago);
    else if (how == FW_TRAJ_END_FAULT && fault == FW_FAULT_ESTOP)
        snprintf(buf, cap, "rejected: ended: %s: its trajectory was ended by an e-stop %s before this row came", cmd,
                 ago);
    else if (how == FW_TRAJ_END_FAULT)
        snprintf(buf, cap, "rejected: ended: %s: its trajectory was ended by a %s fault %s before this row came", cmd,
                 proto_enum_name(proto_fault_names, fault), ago);
    else
        snprintf(buf, cap,
                 "rejected: ended: %s: no trajectory of this row's identity is running (a trajectory starts with a "
                 "row flagged first, taken while the controller is idle)",
                 cmd);
}

/* REJECT's where, thousandths, as a percentage. */
static double percent(int where)
{
    return where * 100.0 / PROTO_PER_MILLE;
}

const char *reject_text(const proto_message *r, char *buf, size_t cap)
{
    const int function = r->v[0], reason = r->v[2], scissor = r->v[3], kin = r->v[4], field = r->v[5],
              where = r->v[6];
    const char *rn = proto_enum_name(proto_reason_names, reason);
    const char *cmd = command_name(function);
    switch (reason) {
    case FW_REASON_KINEMATICS:
        snprintf(buf, cap,
                 "rejected: kinematics: %s: scissor %d is %s at %.1f%% of the path (the pose, or the "
                 "path to it, leaves the workspace with its margins; 'tse-kin ik' shows the pose's status)",
                 cmd, scissor, proto_enum_name(proto_kin_status_names, kin), percent(where));
        break;
    case FW_REASON_TOO_LONG:
        if (field == 0)
            snprintf(buf, cap,
                     "rejected: too_long: %s: the move would last longer than the %d s a move may (its speed too "
                     "slow, or its duration too long once stretched to the slide limits): ask a faster speed or a "
                     "shorter duration, or split the move",
                     cmd, where);
        else
            snprintf(buf, cap,
                     "rejected: too_long: %s: the path comes so near a limit (scissor %d %s) at %.1f%% of its "
                     "length that the controller cannot check so long a move within one frame: split it into "
                     "shorter moves, or keep the path farther from that limit",
                     cmd, scissor, proto_enum_name(proto_kin_status_names, kin), percent(where));
        break;
    case FW_REASON_TIMING: {
        const int limit = field / FW_REJECT_LIMIT, slide = field % FW_REJECT_LIMIT;
        const double ratio = where / (double)PROTO_PER_MILLE;
        const char *words = proto_code_words(proto_slide_limits, limit);
        if (limit == FW_LIMIT_SLIDE_AMAX)
            snprintf(buf, cap,
                     "rejected: timing: %s: slide %s (scissor %d) would need %.2f times %s, of which a path "
                     "may use %.2f (the rest is kept for braking in a stop): the speed changes too abruptly "
                     "here. Between points the plate moves at constant speed, so every change of speed at a "
                     "point must be small: ease in and out, sample a smooth path (10-50 ms apart), and start "
                     "at rest where the plate is",
                     cmd, reject_slide_name(slide), scissor, ratio, words, (double)FW_PATH_MARGIN);
        else if (words)
            snprintf(buf, cap,
                     "rejected: timing: %s: slide %s (scissor %d) would need %.2f times %s: give this point at "
                     "least %d%% more time from the previous one",
                     cmd, reject_slide_name(slide), scissor, ratio, words,
                     where > PROTO_PER_MILLE ? ((where - PROTO_PER_MILLE) * 100 + PROTO_PER_MILLE - 1) / PROTO_PER_MILLE : 1);
        else
            snprintf(buf, cap,
                     "rejected: timing: %s: slide %s (scissor %d) would need %.2f times a limit this tsectl does "
                     "not know (code %d; a firmware newer than tsectl?)",
                     cmd, reject_slide_name(slide), scissor, ratio, limit);
        break;
    }
    case FW_REASON_STATE:
        snprintf(buf, cap, "rejected: state: %s is not taken while the controller is %s: %s", cmd,
                 proto_enum_name(proto_state_names, field), state_advice(function, field));
        break;
    case FW_REASON_NOT_HOMED:
        snprintf(buf, cap, "rejected: not_homed: %s: the slides have no zero yet: home first ('tsectl home --wait')",
                 cmd);
        break;
    case FW_REASON_RANGE: {
        const proto_def *d = proto_lookup((uint8_t)function, PROTO_TO_CONTROLLER);
        if (d && field < d->nfields)
            snprintf(buf, cap, "rejected: range: %s.%s is outside [%ld, %ld] (raw units)", cmd, d->fields[field].name,
                     (long)d->fields[field].min, (long)d->fields[field].max);
        else
            snprintf(buf, cap, "rejected: range: %s: field %d is outside its range", cmd, field);
        break;
    }
    case FW_REASON_PARAM_UNKNOWN:
        snprintf(buf, cap, "rejected: param_unknown: this controller has no parameter %d (firmware older than tsectl?)",
                 field);
        break;
    case FW_REASON_PARAM_RANGE:
        snprintf(buf, cap, "rejected: param_range: %s is outside its range (see 'tsectl params list')",
                 field < FP_COUNT ? fw_param_table[field].name : "the parameter");
        break;
    case FW_REASON_PARAM_SET: {
        const char *words = proto_code_words(proto_param_rules, where);
        if (words)
            snprintf(buf, cap, "rejected: param_set: %s: %s; nothing was changed",
                     field < FP_COUNT ? fw_param_table[field].name : "the parameter", words);
        else
            snprintf(buf, cap,
                     "rejected: param_set: %s: the set breaks a rule this tsectl does not know (code %d; a "
                     "firmware newer than tsectl?); nothing was changed",
                     field < FP_COUNT ? fw_param_table[field].name : "the parameter", where);
        break;
    }
    case FW_REASON_STORAGE:
        snprintf(buf, cap,
                 "rejected: storage: the controller could not write its parameter store (on the board a "
                 "flash erase or write failed; in tse-sim, no --params FILE or the file could not be "
                 "written): nothing was saved, the running parameters are unchanged but are lost at "
                 "power-off");
        break;
    case FW_REASON_QUEUE_FULL:
        snprintf(buf, cap, "rejected: queue_full: %s: the trajectory queue is full (send when STATUS shows room)", cmd);
        break;
    case FW_REASON_STALE:
        snprintf(buf, cap,
                 "rejected: stale: %s: its sequence number is not newer than the last accepted (another "
                 "host commanding this node?)",
                 cmd);
        break;
    case FW_REASON_ORDER:
        if (function == proto_table[PM_BOOT_WRITE].function) {
            snprintf(buf, cap,
                     "rejected: order: %s: not the next block of the image (the bootloader expects block %d): a "
                     "block before it was refused or lost; nothing was written (send again from that block)",
                     cmd, where);
            break;
        }
        snprintf(buf, cap,
                 "rejected: order: %s: not the next row of its trajectory (the controller expects sequence number "
                 "%d): a row before it was refused or lost; nothing was taken (send again from the first row not "
                 "acknowledged)",
                 cmd, field);
        break;
    case FW_REASON_ENDED:
        ended_text(buf, cap, cmd, field & 15, field >> 4, where);
        break;
    case FW_REASON_CRC:
        snprintf(buf, cap,
                 "rejected: crc: %s: the CRC-32 of what arrived differs from the one declared (frames damaged or "
                 "lost on the bus, or an image whose header's CRC is wrong); nothing of it is bootable",
                 cmd);
        break;
    case FW_REASON_ADDRESS:
        snprintf(buf, cap, "rejected: address: %s: block %d lies beyond the image's erased length; nothing written",
                 cmd, where);
        break;
    case FW_REASON_LENGTH:
        snprintf(buf, cap,
                 "rejected: length: %s: a length that cannot be (an image not of whole words, shorter than its "
                 "header or longer than the application area; a block with other than its frames, %d expected or "
                 "received; blocks missing before VERIFY); nothing written",
                 cmd, where);
        break;
    case FW_REASON_HEADER:
        snprintf(buf, cap,
                 "rejected: header: %s: block 0 holds no image header of a version this bootloader reads, or "
                 "one whose length differs from the one erased for (field %d); nothing written",
                 cmd, field);
        break;
    case FW_REASON_BOARD:
        snprintf(buf, cap, "rejected: board: %s: the image is built for another board; nothing written", cmd);
        break;
    case FW_REASON_FLASH:
        snprintf(buf, cap,
                 "rejected: flash: %s: a flash erase or program failed (sector or block %d); the update must "
                 "start again from its erase",
                 cmd, where);
        break;
    case FW_REASON_NO_IMAGE:
        snprintf(buf, cap,
                 "rejected: no_image: %s: the application area holds no whole image for this board (%s: "
                 "boot/image.h); the bootloader stays",
                 cmd, boot_image_status_name((boot_image_status)field));
        break;
    case FW_REASON_INCOMPLETE:
        snprintf(buf, cap, "rejected: incomplete: %s: a part of its pose did not arrive (frames lost on the bus?)", cmd);
        break;
    default:
        snprintf(buf, cap, "rejected: %s: %s (a protocol mismatch between tsectl and the controller?)", rn, cmd);
        break;
    }
    return buf;
}
