/* Where the controller's motion stands: what the control tick runs, and homing's phases.  Types
 * only: the controller keeps them, its inspection (fw/inspect.h) reports them. */
#ifndef FW_PHASES_H
#define FW_PHASES_H

/* What the control tick runs. */
typedef enum { FW_SRC_NONE, FW_SRC_MOVE, FW_SRC_TRAJ, FW_SRC_JOINT } fw_source;

/* Homing: first every slide finds its switch on its own (HOME_SWITCHES), then, at rest, the path
 * to the home pose is checked by the controller's thread (HOME_PATH_CHECK), then all six go to
 * the home pose together (HOME_TO_POSE). */
typedef enum { HOME_SWITCHES, HOME_PATH_CHECK, HOME_TO_POSE } fw_home_phase;

/* One slide while finding its switch. */
typedef enum {
    HOME_AXIS_LEAVE,   /* started on the switch: up at the homing speed, past the release */
    HOME_AXIS_SEEK,    /* down at the homing speed to the press, then braking */
    HOME_AXIS_RELEASE, /* up at the creep speed to the release edge */
    HOME_AXIS_DONE     /* edge latched */
} fw_home_axis;

#endif
