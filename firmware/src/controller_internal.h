/* The controller's layout, private to firmware/src: who owns what (fw/runtime.h names the
 * contexts).
 *
 *   hal, cfg   set by fw_init; read by every context.
 *   tick       the control tick's: written in its context only (and by fw_init, and by the
 *              thread's hand-over taken in place where one context runs everything).  Nothing
 *              else reads it but through the published view, except the accessors (fw/inspect.h)
 *              where nothing runs at once.
 *   th         the thread's: written and read by the thread only.
 *   sh         between the two: atomics, and what they guard (handover.h, publish.h).
 *   sg         the step generator: the tick produces, the step interrupt consumes (fw/stepgen.h).
 *
 * The thread's copy of the parameters (th.params, geom, lim) is the tick's as of the last set the
 * tick adopted: sets change only through the hand-over, which updates both. */
#ifndef FW_CONTROLLER_INTERNAL_H
#define FW_CONTROLLER_INTERNAL_H

#include <stdatomic.h>
#include <stdbool.h>
#include <stdint.h>

#include "fw/limits.h"
#include "fw/phases.h"
#include "fw/platform.h"
#include "fw/move.h"
#include "fw/params.h"
#include "fw/profile.h"
#include "fw/proto.h"
#include "fw/stepgen.h"
#include "fw/traj.h"
#include "fw/traj_stop.h"
#include "fw/types.h"
#include "hal/can.h"
#include "tse/geometry.h"

/* ---- The control tick's ------------------------------------------------------------------- */

/* Homing's progress (homing.c). */
typedef struct {
    bool active;        /* homing runs, or is being stopped */
    bool abort;         /* a stop or a fault asked it to come to rest */
    fw_home_phase phase;
    uint8_t axis[6];    /* fw_home_axis of each slide */
    uint8_t released;   /* leaving slides whose switch has released */
    uint8_t hit;        /* seeking slides whose switch has been pressed */
    tse_real v[6];      /* joint speeds [m/s], signed */
    tse_real s[6];      /* joint travel since homing began [m] */
    tse_real mark[6];   /* travel where the slide's phase began (leaving: where it released) */
    int32_t start_steps[6];
    int32_t edge_steps[6]; /* steps emitted when the release edge was seen */
    uint32_t path_ask;     /* HOME_PATH_CHECK: the number it asked the thread's check by (0: not yet) */
} fw_homing;

/* A joint-space move (after homing, the robot is not yet at a pose the planner can start from). */
typedef struct {
    tse_real from[6], to[6];
    fw_profile prof; /* of u in [0, 1] */
} fw_joint_move;

typedef struct {
    fw_state state;
    fw_fault fault;         /* latched fault (FW_FAULT_NONE when none) */
    fw_fault pending_fault; /* fault to latch once the controlled stop ends */
    bool homed;
    bool drives_on;
    bool pose_known;

    fw_param_set params;
    tse_geometry geom;
    fw_limits lim;

    tse_real pose[6];       /* pose of the latest segment setpoint */
    tse_real q[6];          /* its slides [m] */
    tse_real q_prev[6];     /* the setpoint before (for the current slide speeds) */

    /* Motion (motion.c) */
    fw_source src;
    fw_move move;
    fw_move next;           /* a move committed while `move` runs, blended into it */
    bool has_next;
    uint32_t blend_k0;      /* segment of `move` at which `next` starts */
    fw_joint_move joint;
    tse_real tau;           /* path time of the running source [s] */
    bool stopping;
    tse_real stop_t, stop_T;/* time into the stop ramp, its length */
    fw_traj_stop traj_stop; /* a trajectory's ramp as it runs (its law: fw/traj_stop.h) */
    uint32_t segments_run;
    fw_homing home;

    /* The trajectory queue and its life (traj_life.c): rows join it by the hand-over. */
    fw_traj_queue traj;
    bool traj_open;         /* from its first row until it ends */
    bool traj_clock;        /* its clock runs (kept as it was once it ends) */
    uint8_t traj_id;        /* the open trajectory's identity */
    uint32_t traj_rows;     /* rows it took */

    /* Supervision (supervise.c) */
    uint32_t bus_off_seen;  /* the CAN controller's bus-off count at the last supervision */
    uint32_t overruns_seen; /* the step generator's overrun count at the last supervision */
    bool estop_in;          /* the e-stop input open, as last read */
    bool switches_off;      /* the switches disagree with the step count, as last read */
    bool error_passive;     /* the CAN controller, as last read */
} fw_tick;

/* ---- The hand-over (handover.c) ----------------------------------------------------------- */

/* A parameter set judged and prepared for this controller's rates (adopt.h). */
typedef struct {
    fw_param_set s;
    tse_geometry g;
    fw_limits lim;
    stepgen_config sc;
} fw_prepared_params;

/* A command for the tick: the message it came as (the tick judges it again by the state table)
 * and what the thread prepared for it. */
typedef struct {
    proto_msg msg;
    uint8_t judged; /* fw_state: the state the thread judged it in (its view) */
    union {
        struct {
            fw_move mv;
            bool successor;  /* planned from the end of the running move */
            bool blend;      /* ... and blended into it from segment k0 (else after it) */
            uint32_t k0;
        } move;
        struct {
            fw_traj_point p;
            bool first;      /* starts a trajectory of identity id */
            uint8_t id;
        } row;
        fw_prepared_params params;
    } u;
} fw_request;

typedef struct {
    fw_reason reason;     /* FW_REASON_NONE: taken */
    fw_move_start start;  /* a move: how it starts */
    fw_param_rule rule;   /* a parameter set refused: the rule */
} fw_verdict;

/* ---- Published by the tick for the thread (publish.c) -------------------------------------- */

enum {
    FW_VIEW_HOMED = 1u << 0,
    FW_VIEW_DRIVES = 1u << 1,
    FW_VIEW_POSE_KNOWN = 1u << 2,
    FW_VIEW_STOPPING = 1u << 3,
    FW_VIEW_HAS_NEXT = 1u << 4,
    FW_VIEW_ESTOP_IN = 1u << 5,
    FW_VIEW_SWITCHES_OFF = 1u << 6,
    FW_VIEW_ERROR_PASSIVE = 1u << 7,
};

typedef struct {
    uint8_t state, fault, src, flags; /* fw_state, fw_fault, fw_source, FW_VIEW_* */
    uint32_t traj_depth;
    uint32_t segments_run;
    int32_t pos[6];       /* steps emitted */
    tse_real pose[6], q[6];
} fw_view;

#define FW_VIEW_WORDS ((sizeof(fw_view) + 3u) / 4u)

/* How a trajectory ended, from the tick to the thread (which sends TRAJ_END). */
typedef struct {
    uint8_t id;
    uint8_t how;   /* fw_traj_end */
    uint8_t fault; /* fw_fault, for FW_TRAJ_END_FAULT */
    uint32_t rows;
    uint64_t us;   /* when */
} fw_traj_ended;

#define FW_ENDED_RING 4u /* a power of two */

typedef struct {
    /* One command at a time: the thread fills req and bumps posted; the tick fills verdict and
     * sets taken to posted. */
    _Atomic uint32_t posted, taken;
    fw_request req;
    fw_verdict verdict;
    /* The view: a sequence counter, odd while the tick writes. */
    _Atomic uint32_t view_seq;
    _Atomic uint32_t view_words[FW_VIEW_WORDS];
    /* Ends of trajectories: the tick appends (ended_in), the thread takes (ended_out). */
    fw_traj_ended ended[FW_ENDED_RING];
    _Atomic uint32_t ended_in, ended_out;
    /* The last heartbeat: the thread (and ENABLE in the tick) store, the tick's watchdog reads. */
    _Atomic uint32_t heartbeat_us;
    /* When the thread last found the bus empty: the clock read just before the receive that
     * returned nothing, so every heartbeat that reached the bus before it is in heartbeat_us.  The
     * watchdog judges the host's silence up to here, not up to the tick's own clock (supervise.c). */
    _Atomic uint32_t bus_read_us;
    /* The thread's progress (fw_thread_progress). */
    _Atomic uint32_t progress;
    /* Homing's final move's path, checked in the thread (homing.h): the tick writes path_from and
     * then bumps path_asked (release); the thread checks, writes path_ok and then stores
     * path_asked in path_answered (release).  The tick writes path_from only when the two agree. */
    _Atomic uint32_t path_asked, path_answered;
    tse_real path_from[6];
    bool path_ok;
    /* fw_estop_isr ran; the tick still to complete it (fw_estop). */
    atomic_bool estop_request;
} fw_shared;

/* ---- The thread's ------------------------------------------------------------------------- */

#define FW_INBOX 16u

typedef struct {
    fw_param_set params;
    tse_geometry geom;
    fw_limits lim;

    /* Staged pose and commits */
    uint8_t stage_seq;
    uint8_t stage_have;     /* bit 0: A, 1: B, 2: C */
    int32_t stage_v[6];
    uint8_t last_seq;       /* last accepted commit */
    bool any_commit;
    fw_move last_move;      /* the move last handed over: a successor starts from its end */

    /* Trajectory rows (traj_rows.c): the validator, and the life as the thread knows it */
    fw_traj_check traj;
    fw_traj_check traj_after; /* the validator once the row being judged is taken */
    bool open;              /* from its first row until its end is collected */
    uint8_t id;             /* the open trajectory's identity */
    uint8_t next_seq;       /* the sequence number its next row must carry */
    fw_traj_end ended;      /* how the last one ended (FW_TRAJ_END_NONE: none has) */
    fw_fault ended_fault;
    uint8_t ended_id;
    uint32_t ended_rows;
    uint64_t ended_us;

    /* Periodic frames */
    uint64_t next_status_us, next_telemetry_us;
    uint16_t counter;

    /* Frames taken off the bus during a validation, waiting for their turn (inbox.c) */
    hal_can_frame inbox[FW_INBOX];
    unsigned in_head, in_count;
    bool watch_moving;      /* a STOP ends the validation under way */
    bool abandon;           /* it was ended: a STOP or an e-stop came */

    fw_view view;           /* the tick's state as last read */
    bool boot_requested;    /* BOOT_ENTER was acknowledged: the platform restarts into its bootloader */
} fw_thread;

struct fw_controller {
    fw_hal hal;
    fw_config cfg;
    fw_tick tick;
    fw_thread th;
    fw_shared sh;
    stepgen sg;
};

_Static_assert(sizeof(struct fw_controller) <= FW_CONTROLLER_BYTES, "fw_controller_mem too small for the controller");
_Static_assert(FW_CONTROLLER_BYTES - sizeof(struct fw_controller) < 1024u,
               "fw_controller_mem more than 1 KiB larger than the controller: shrink FW_CONTROLLER_BYTES");

/* The state changes of the tick's state machine all write here. */
static inline void fw_set_state(fw_controller *c, fw_state s)
{
    c->tick.state = s;
}

/* The low 32 bits of the clock in microseconds: what the heartbeat is kept as. */
static inline uint32_t fw_now32(const fw_controller *c)
{
    return (uint32_t)c->hal.clock.now_us(c->hal.clock.ctx);
}

static inline uint64_t fw_now(const fw_controller *c)
{
    return c->hal.clock.now_us(c->hal.clock.ctx);
}

#endif
