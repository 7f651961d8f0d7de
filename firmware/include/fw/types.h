/* Enumerations shared by the controller and the wire.  Their values travel in CAN frames:
 * append, never renumber. */
#ifndef FW_TYPES_H
#define FW_TYPES_H

/* The longest a move may last [s], stretched or not: MOVE_COMMIT's longest duration, one hour.  A
 * slower one (a move of metres at micrometres a second) is refused TOO_LONG (fw/move.h). */
#define FW_MOVE_MAX_S 3600

typedef enum {
    FW_STATE_BOOT = 0,
    FW_STATE_DISABLED = 1,
    FW_STATE_HOMING = 2,
    FW_STATE_IDLE = 3,
    FW_STATE_MOVING = 4,
    FW_STATE_STOPPING = 5,
    FW_STATE_FAULT = 6,
    FW_STATE_ESTOP = 7,
    FW_STATE_COUNT
} fw_state;

typedef enum {
    FW_FAULT_NONE = 0,
    FW_FAULT_WATCHDOG = 1,     /* host heartbeat silent past the timeout */
    FW_FAULT_LIMIT = 2,        /* outside homing: a high-end switch pressed, or (once homed) a low
                                * homing switch that disagrees with the step count (pressed well
                                * above its position, or released well below it): lost steps or
                                * a broken switch; the zero is dropped */
    FW_FAULT_BUS_OFF = 3,      /* the CAN controller went bus-off */
    FW_FAULT_PLANNER = 4,      /* the inverse kinematics failed on a segment in motion */
    FW_FAULT_STEP_OVERRUN = 5, /* a segment asked the step generator for more than it can */
    FW_FAULT_HOMING = 6,       /* a switch not found within the stroke, or not released */
    FW_FAULT_ESTOP = 7,        /* the e-stop input or command (latched until cleared) */
    FW_FAULT_UNDERRUN = 8,     /* the trajectory queue ran dry while moving */
    FW_FAULT_PLANT = 9,        /* the simulator's plant saw a physical invariant broken */
    FW_FAULT_HARDWARE = 10,    /* a hardware wait timed out or a peripheral failed at start-up:
                                * clock, CAN controller, flash (reported by the board) */
    FW_FAULT_COUNT
} fw_fault;

/* How an accepted move starts (MOVE_INFO frame). */
typedef enum {
    FW_START_REST = 0,    /* from rest */
    FW_START_BLENDED = 1, /* blended into the running move's deceleration */
    FW_START_AFTER = 2,   /* after the running move, back to back: a blend would break a limit */
    FW_START_COUNT
} fw_move_start;

/* What set an accepted move's pace (MOVE_INFO frame): the request itself, a plate limit, or a slide
 * limit that stretched it.  Named after the limit parameters. */
typedef enum {
    FW_BOUND_ASKED = 0,        /* the duration or plate speed asked for */
    FW_BOUND_PLATE_VMAX = 1,
    FW_BOUND_PLATE_AMAX = 2,
    FW_BOUND_PLATE_JMAX = 3,
    FW_BOUND_PLATE_WMAX = 4,
    FW_BOUND_PLATE_DWMAX = 5,
    FW_BOUND_PLATE_JMAX_ANGULAR = 6, /* the rotation's ramps: plate_dwmax x plate_jmax / plate_amax */
    FW_BOUND_SLIDE_VMAX = 7,   /* a slide's speed limit, slide_vmax */
    FW_BOUND_SLIDE_AMAX = 8,   /* a slide's acceleration limit */
    FW_BOUND_STEP_GENERATOR = 9, /* a slide's speed limit in effect, the step generator's (fw/limits.h) */
    FW_BOUND_COUNT
} fw_move_bound;

/* Why a command was refused (REJECT frame). */
typedef enum {
    FW_REASON_NONE = 0,
    FW_REASON_BAD_LENGTH = 1,    /* frame length differs from the table's */
    FW_REASON_UNKNOWN = 2,       /* no such message for a controller */
    FW_REASON_RANGE = 3,         /* a field outside its range (field index in the reject) */
    FW_REASON_STATE = 4,         /* not accepted in the current state */
    FW_REASON_NOT_HOMED = 5,     /* motion before homing */
    FW_REASON_INCOMPLETE = 6,    /* commit without all three pose parts of its sequence */
    FW_REASON_STALE = 7,         /* sequence number not newer than the last accepted */
    FW_REASON_KINEMATICS = 8,    /* pose or path outside the workspace (scissor, status) */
    FW_REASON_QUEUE_FULL = 9,    /* trajectory queue full */
    FW_REASON_PARAM_UNKNOWN = 10,
    FW_REASON_PARAM_RANGE = 11,
    FW_REASON_PARAM_SET = 12,    /* value in range, but the geometry it gives is invalid */
    FW_REASON_STORAGE = 13,      /* parameters could not be saved */
    FW_REASON_TIMING = 14,       /* a timed point asks for more than the slide limits allow */
    FW_REASON_ORDER = 15,        /* a trajectory row that is not its trajectory's next: a row before
                                  * it was refused or lost (nothing taken; send again from that one) */
    FW_REASON_ENDED = 16,        /* a row of a trajectory that is not running: it ended (a STOP, a
                                  * fault, an underrun, an e-stop, or its last row), or never began */
    FW_REASON_TOO_LONG = 17,     /* a move beyond what one frame may validate: longer than
                                  * FW_MOVE_MAX_S, or too long to prove near a limit (fw/reject.h) */
    /* The bootloader's (docs/protocol.md, Updating the firmware; boot/update.h): */
    FW_REASON_CRC = 18,          /* a block's or the image's CRC-32 differs from the one declared */
    FW_REASON_ADDRESS = 19,      /* a block outside the application area or the erased length */
    FW_REASON_LENGTH = 20,       /* an image or block length that cannot be (not whole words, too
                                  * long, frames other than the block's, blocks missing) */
    FW_REASON_HEADER = 21,       /* block 0 without a valid image header, or one whose length
                                  * differs from the one erased for */
    FW_REASON_BOARD = 22,        /* an image built for another board */
    FW_REASON_FLASH = 23,        /* a flash erase or program failed */
    FW_REASON_NO_IMAGE = 24,     /* BOOT_START with no valid application */
    FW_REASON_COUNT
} fw_reason;

/* How a streamed trajectory ended (TRAJ_END, and the REJECT of a row of it that came after). */
typedef enum {
    FW_TRAJ_END_NONE = 0,  /* not known to have run: no trajectory of that identity ended last */
    FW_TRAJ_END_DONE = 1,  /* it ran to its last row */
    FW_TRAJ_END_STOP = 2,  /* a STOP ended it */
    FW_TRAJ_END_FAULT = 3, /* a fault ended it (the fault travels with it: e-stop, underrun, ...) */
    FW_TRAJ_END_COUNT
} fw_traj_end;

#endif
