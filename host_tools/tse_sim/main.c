/* tse-sim: the controller firmware on Linux SocketCAN, driving a simulated plant.
 *
 *   tse-sim --iface vcan0 [--node N] [--params FILE] [--start S] [--fault SPEC]
 *           [--step-hz HZ] [--segment-hz HZ]
 *   tse-sim --write-params FILE
 *   tse-sim --version
 *
 * The firmware runs unchanged on hal/posix, in the board's contexts (fw/runtime.h): a tick thread
 * runs the 1 kHz control tick, each followed by its 200 step interrupts against the plant (other
 * rates with --step-hz and --segment-hz, as a board built otherwise would run them) (whose
 * clock is the step count, so the simulated physics is exact whatever the scheduler does); the
 * main thread is the controller's thread (frames, planning, validation), waiting on the bus; a
 * late period waits (bounded) until it has taken the frames that came before the period
 * (hal_posix/ticker.h).
 * State changes, faults and plant breaches are logged on stdout from the tick thread; SIGINT or
 * SIGTERM stops it cleanly.  The parameter file is the SI text of
 * host_tools/params (param_store.h): one it cannot read or the controller refuses stops it before
 * it starts (exit 2), and is never written.  --fault puts hal/fault between the firmware and the
 * bus, the switches and the plant's drives (fault_spec.h); its windows are logged as they open and
 * close, and what it did when tse-sim stops. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <sched.h>
#include <stdatomic.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "fw/controller.h"
#include "fw/inspect.h"
#include "fw/limits.h"
#include "fw/proto.h"
#include "fw/runtime.h"
#include "hal_posix/plant.h"
#include "hal_posix/posix_hal.h"
#include "hal_posix/ticker.h"
#include "text.h"
#include "estop_watch.h"
#include "fault_spec.h"
#include "param_store.h"
#include "param_text.h"
#include "tse_version.h"

/* The controller's rates: the built-in ones (fw/limits.h) unless --step-hz or --segment-hz say
 * otherwise; it reports them in INFO, which tsectl and tse.can judge its paths and sets at. */
static fw_rates rates = FW_RATES_BUILT_IN;
/* The longest a late control period waits for this thread to take the frames that came before it
 * (hal_posix/ticker.h), in this thread's CPU time: 50 ms, a row's validation many times over even
 * in a VM under TCG (whose threads are charged the time the host takes the VM's CPU away), short
 * beside a move for a thread busy validating a blend.  Its wall-time backstop is 1 s. */
#define LATE_WAIT_US 50000u

static posix_ticker ticker = {.fd = -1};
static volatile sig_atomic_t quit;

static void on_signal(int sig)
{
    (void)sig;
    quit = 1;
}

typedef struct {
    fw_controller_mem fw_mem;
    fw_controller *fw;
    tse_plant plant;
    fw_state last_state;
    fw_fault last_fault;
    uint32_t reported;
    bool awaiting_first_step;
    uint64_t accepted_tick;   /* plant tick at which motion was accepted */
    estop_watch estop;        /* which steps came while an e-stop held */
    bool faulty;              /* --fault given: the three wrappers below sit in the HAL */
    fault_can fcan;
    fault_inputs finputs;
    fault_stepper fstepper;
    uint8_t windows_open;     /* which fault windows held at the last control call */
} sim;


static const char *name_of(const proto_enum_entry *t, int v)
{
    return proto_enum_name(t, v);
}

static void log_pose(sim *s, const char *why)
{
    if (plant_update_pose(&s->plant))
        printf("tse-sim: %s: plate %.6f %.6f %.6f m, %.6f %.6f %.6f rad\n", why, s->plant.pose[0], s->plant.pose[1],
               s->plant.pose[2], s->plant.pose[3], s->plant.pose[4], s->plant.pose[5]);
}

/* A line whenever one of --fault's windows opens or closes. */
static void log_fault_windows(sim *s)
{
    if (!s->faulty)
        return;
    const struct {
        const fault_window *w;
        const char *what;
    } win[] = {
        {&s->fcan.cfg.silence, "host silence (every frame to the controller lost)"},
        {&s->fcan.cfg.bus_off, "bus-off"},
        {&s->finputs.cfg.estop, "e-stop input open"},
        {&s->finputs.cfg.limit, "high-end limit switch pressed"},
        {&s->fstepper.cfg.stall, "stalled slide (its steps not taken)"},
    };
    const uint64_t t[] = {fault_clock_us(&s->fcan.clock), fault_clock_us(&s->fcan.clock),
                          fault_clock_us(&s->finputs.clock), fault_clock_us(&s->finputs.clock),
                          fault_clock_us(&s->fstepper.clock)};
    for (unsigned i = 0; i < sizeof win / sizeof win[0]; ++i) {
        const bool open = fault_window_holds(win[i].w, t[i]);
        const bool was = (s->windows_open >> i) & 1u;
        if (open != was)
            printf("tse-sim: fault: %s %s at t = %.3f s\n", win[i].what, open ? "begins" : "ends", (double)t[i] * 1e-6);
        s->windows_open = (uint8_t)(open ? s->windows_open | (1u << i) : s->windows_open & ~(1u << i));
    }
}

static void log_fault_counts(const sim *s)
{
    if (!s->faulty)
        return;
    const fault_can_stats *c = &s->fcan.stats;
    printf("tse-sim: faults: of %u frames to the controller %u delivered; dropped %u, duplicated %u, reordered %u, "
           "delayed %u, corrupted %u (payload %u, length %u, identifier %u), lost to silence %u, lost while "
           "bus-off %u; %u sends refused while bus-off; %llu steps not taken\n",
           c->received, c->delivered, c->faults[FAULT_DROP], c->faults[FAULT_DUP], c->faults[FAULT_REORDER],
           c->faults[FAULT_DELAY], c->faults[FAULT_CORRUPT], c->corrupt_payload, c->corrupt_length, c->corrupt_id,
           c->silenced, c->bus_off_lost, c->send_refused, (unsigned long long)s->fstepper.lost_total);
}

/* The tick thread: the control tick, then what tse-sim watches of it (fw/runtime.h: after
 * fw_control_tick, in its context). */
static void control(void *arg)
{
    sim *s = arg;
    log_fault_windows(s);
    fw_control_tick(s->fw);
    if (s->plant.breaches & ~s->reported) {
        printf("tse-sim: plant: %s (breaches 0x%x)\n", s->plant.first_breach, s->plant.breaches);
        s->reported = s->plant.breaches;
        fw_report_fault(s->fw, FW_FAULT_PLANT);
    }
    if (s->awaiting_first_step && s->plant.first_after_mark) {
        printf("tse-sim: first step %.3f ms after the command was taken\n",
               (double)(s->plant.first_after_mark - s->accepted_tick) * 1e3 / rates.step_hz);
        s->awaiting_first_step = false;
    }
    uint64_t after;
    if (s->plant.pulses && estop_watch_pulse(&s->estop, s->plant.last_pulse_tick, &after))
        printf("tse-sim: a step %.3f ms after the e-stop\n", (double)after * 1e3 / rates.step_hz);
    const fw_state state = fw_state_of(s->fw);
    const fw_fault fault = fw_fault_of(s->fw);
    if (state != s->last_state || fault != s->last_fault) {
        if (state == FW_STATE_MOVING || state == FW_STATE_HOMING) {
            s->awaiting_first_step = true;
            s->accepted_tick = s->plant.tick;
            plant_mark(&s->plant);
            printf("tse-sim: motion accepted at t = %.3f s\n", (double)s->plant.tick / rates.step_hz);
        }
        if (s->last_state == FW_STATE_ESTOP && state != FW_STATE_ESTOP)
            estop_watch_cleared(&s->estop, s->plant.tick);
        if (state == FW_STATE_ESTOP && s->last_state != FW_STATE_ESTOP) {
            estop_watch_taken(&s->estop, s->plant.tick);
            printf("tse-sim: e-stop taken; the last step was %.3f ms before it\n",
                   (double)(s->plant.tick - s->plant.last_pulse_tick) * 1e3 / rates.step_hz);
        }
        printf("tse-sim: state %s, fault %s\n", name_of(proto_state_names, state), name_of(proto_fault_names, fault));
        if (state == FW_STATE_IDLE && fw_homed_of(s->fw))
            log_pose(s, "at rest");
        s->last_state = state;
        s->last_fault = fault;
    }
    fflush(stdout);
}

/* A step tick under way in the tick thread.  On the board nothing runs beside a step tick: the
 * controller's thread, halting stepping for an ESTOP frame, switches the drives off after any
 * step tick that decided its pulses before the halt.  Here the two are threads: the switch waits
 * for that step tick (at most one, a microsecond) before it reaches the drives. */
static atomic_bool in_step;
static hal_stepper drives;

static void step(void *arg)
{
    sim *s = arg;
    atomic_store(&in_step, true);
    atomic_thread_fence(memory_order_seq_cst); /* before the step generator reads its halt */
    fw_step_tick(s->fw);
    atomic_store(&in_step, false);
    plant_tick(&s->plant);
}

static void enable_after_step(void *ctx, bool on)
{
    if (!on)
        while (atomic_load(&in_step))
            sched_yield();
    drives.enable(ctx, on);
}

/* The controller's thread waits for the tick (fw_config.await): the next control call. */
static void await_tick(void *ctx)
{
    posix_ticker_await(ctx);
}

static int usage(const char *why)
{
    fprintf(stderr,
            "tse-sim: %s\n"
            "usage: tse-sim --iface IFACE [--node N] [--params FILE] [--start S] [--fault SPEC]\n"
            "               [--step-hz HZ] [--segment-hz HZ]\n"
            "       tse-sim --write-params FILE\n"
            "       tse-sim --version\n"
            "  --node N             the CAN node id, 1..15, over the parameter `node` (which a\n"
            "                       PARAM_SET and PARAM_SAVE change for the next start)\n"
            "  --params FILE        the controller's parameters, as 'name = value' text in SI units\n"
            "                       (m, rad, m/s, ...; or as the name says: _ms, _ns, _kbps, _deg);\n"
            "                       names left out keep their defaults; a file that cannot be read\n"
            "                       or holds a refused value or set stops tse-sim before it starts\n"
            "                       (exit 2, naming the line).  A missing FILE means the defaults;\n"
            "                       PARAM_SAVE writes the whole set to it\n"
            "  --write-params FILE  write the defaults, one commented line per parameter, to FILE\n"
            "                       as a template and exit (refused if FILE exists)\n"
            "  --start S            slide positions at power-up [m] (default 0.05: below the homing\n"
            "                       switches at 0.2 m, so homing first leaves them)\n"
            "  --step-hz HZ         step interrupts per second (default %u)\n"
            "  --segment-hz HZ      control segments per second (default %u): a segment must be whole\n"
            "                       microseconds and whole step interrupts; the controller reports both\n"
            "                       in INFO ('tsectl info'), and the host tools judge paths at them\n"
            "%s",
            why, FW_STEP_HZ, FW_SEGMENT_HZ, fault_spec_help);
    return 2;
}

/* --write-params: the defaults as a template, never over an existing file. */
static int write_template(const char *path)
{
    struct stat sb;
    if (stat(path, &sb) == 0) {
        fprintf(stderr, "tse-sim: %s exists: not overwritten\n", path);
        return 2;
    }
    fw_param_set d;
    fw_params_default(&d);
    char err[768];
    if (param_file_write(path, &d, rates, err, sizeof err) != 0) {
        fprintf(stderr, "tse-sim: %s\n", err);
        return 2;
    }
    printf("tse-sim: wrote the default parameters to %s\n", path);
    return 0;
}

/* A rate option's value: whole hertz, 1 up to 2^32 - 1.  0, or -1. */
static int rate_of(const char *text, uint32_t *hz)
{
    char *end = NULL;
    errno = 0;
    const unsigned long long v = strtoull(text, &end, 10);
    if (!*text || *text == '-' || *end || errno != 0 || v == 0 || v > UINT32_MAX)
        return -1;
    *hz = (uint32_t)v;
    return 0;
}

int main(int argc, char **argv)
{
    const char *iface = NULL, *params = NULL, *write_params = NULL, *fault = NULL;
    static fault_plan plan;
    long node = -1;
    double start = 0.05;
    for (int i = 1; i < argc; ++i) {
        const int v = i + 1 < argc;
        char *end = NULL;
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            usage("simulated TSE controller on SocketCAN");
            return 0;
        } else if (!strcmp(argv[i], "--version")) {
            printf("tse-sim %s\n", TSE_VERSION);
            return 0;
        } else if ((!strcmp(argv[i], "--step-hz") || !strcmp(argv[i], "--segment-hz")) && v) {
            const bool step = !strcmp(argv[i], "--step-hz");
            if (rate_of(argv[++i], step ? &rates.step_hz : &rates.segment_hz) != 0)
                return usage(step ? "--step-hz takes whole hertz above 0" : "--segment-hz takes whole hertz above 0");
        } else if (!strcmp(argv[i], "--iface") && v) {
            iface = argv[++i];
        } else if (!strcmp(argv[i], "--node") && v) {
            node = strtol(argv[++i], &end, 10);
            if (*end || node < 1 || node > 15)
                return usage("--node takes 1..15");
        } else if (!strcmp(argv[i], "--params") && v) {
            params = argv[++i];
        } else if (!strcmp(argv[i], "--write-params") && v) {
            write_params = argv[++i];
        } else if (!strcmp(argv[i], "--fault") && v) {
            char err[256];
            fault = argv[++i];
            if (fault_spec_parse(fault, &plan, err, sizeof err) != 0) {
                fprintf(stderr, "tse-sim: --fault: %s\n", err);
                return usage("bad --fault");
            }
        } else if (!strcmp(argv[i], "--start") && v) {
            if (text_number(argv[++i], &start) != 0 || !(start > -0.01 && start < 0.91))
                return usage("--start takes a slide position in metres inside the stroke");
        } else {
            fprintf(stderr, "tse-sim: unexpected argument '%s'\n", argv[i]);
            return usage("bad arguments");
        }
    }
    if (write_params)
        return write_template(write_params);
    if (!fw_rates_run(rates)) {
        fprintf(stderr,
                "tse-sim: no controller runs at %u Hz step interrupts and %u Hz control segments: a segment must be "
                "whole microseconds (segment_hz divides 1000000) and whole step interrupts (segment_hz divides "
                "step_hz), with step_hz up to %ld and segment_hz up to %ld (INFO's fields)\n",
                rates.step_hz, rates.segment_hz, (long)proto_table[PM_INFO].fields[3].max,
                (long)proto_table[PM_INFO].fields[4].max);
        return usage("bad --step-hz or --segment-hz");
    }
    if (!iface)
        return usage("--iface is needed");

    static sim s;
    static sim_param_store store;
    char err[768];
    if (sim_param_store_open(&store, params, rates, stderr, err, sizeof err) != 0) {
        fprintf(stderr, "tse-sim: %s\n", err);
        return 2;
    }
    /* The controller starts before the bus opens (fw_init sends nothing), so that a parameter
     * file it cannot adopt is refused like any other bad file, whatever the bus. */
    static posix_can can = {.fd = -1};
    fw_hal hal;
    hal.can = posix_can_hal(&can);
    hal.stepper = plant_stepper(&s.plant);
    hal.inputs = plant_inputs(&s.plant);
    hal.clock = posix_clock_hal();
    hal.storage = sim_param_store_hal(&store);
    if (fault) {
        /* The firmware sees the bus, the switches and the drives through the fault layer. */
        s.faulty = true;
        fault_can_init(&s.fcan, &plan.can, hal.can, hal.clock);
        fault_inputs_init(&s.finputs, &plan.inputs, hal.inputs, hal.clock);
        fault_stepper_init(&s.fstepper, &plan.stepper, hal.stepper, hal.clock);
        hal.can = fault_can_hal(&s.fcan);
        hal.inputs = fault_inputs_hal(&s.finputs);
        hal.stepper = fault_stepper_hal(&s.fstepper);
    }
    drives = hal.stepper;
    hal.stepper.enable = enable_after_step;
    /* Without --node, the controller's node parameter (from --params, as saved) gives the id, as on
     * the board; a PARAM_SET of node takes effect at the next start. */
    const fw_config cfg = {node > 0 ? (uint8_t)node : 0u, rates.segment_hz, rates.step_hz, await_tick, &ticker,
                           "tse-sim"};
    s.fw = fw_init(&s.fw_mem, &hal, &cfg);
    if (!s.fw) {
        /* The node and the rates were checked: not even the default set runs at these rates. */
        fprintf(stderr,
                "tse-sim: the controller did not start: not even its default parameters run at %u Hz step "
                "interrupts and %u Hz control segments (step_pulse_ns must end within a step interrupt and leave as "
                "long low; dir_setup_ns must leave room for a step within a control segment)\n",
                rates.step_hz, rates.segment_hz);
        return 2;
    }
    /* fw_init falls back to the defaults when it cannot adopt the stored set: what depends on the
     * controller's rates (the STEP pulse and DIR set-up against the step interrupts) is judged
     * only there.  The file asked for this set: running with another would mislead. */
    if (store.stored && memcmp(fw_params_of(s.fw), &store.set, sizeof store.set) != 0) {
        fprintf(stderr,
                "tse-sim: %s: the controller cannot adopt this set at its %u Hz step interrupts (step_pulse_ns "
                "must end within one and leave as long low before the next step at step_rate_max; dir_setup_ns "
                "must leave room for a step within a %u Hz control period)\n",
                params, rates.step_hz, rates.segment_hz);
        return 2;
    }
    node = fw_config_of(s.fw)->node;
    if (posix_can_open(&can, iface, (uint8_t)node) != 0) {
        fprintf(stderr, "tse-sim: cannot open CAN interface %s: %s\n", iface, strerror(errno));
        return 1;
    }
    /* The plant follows the controller's parameters (stroke, steps per metre, limits, where the
     * homing switches sit, the drivers' timing the controller programmed in fw_init). */
    const double starts[6] = {start, start, start, start, start, start};
    const fw_param_set *fp = fw_params_of(s.fw);
    stepgen_config sc; /* as the controller derived it from the set it adopted */
    if (fw_stepgen_config_from_params(fp, rates.step_hz, rates.segment_hz, &sc) != FW_RULE_NONE) {
        fprintf(stderr, "tse-sim: the controller's own parameter set does not derive its step timing\n");
        return 1;
    }
    plant_config pc = {(double)fp->v[FP_STEPS_PER_M], (double)fp->v[FP_SLIDE_VMAX] / PROTO_UM_PER_M,
                       (double)fp->v[FP_SLIDE_AMAX] / PROTO_UM_PER_M, 0.05, rates.step_hz, sc.min_step_interval,
                       (uint32_t)fp->v[FP_STEP_PULSE_NS], (uint32_t)fp->v[FP_DIR_SETUP_NS], {0}};
    for (int k = 0; k < 6; ++k)
        pc.home_sw[k] = (double)fp->v[FP_HOME_SW_1 + k] / PROTO_UM_PER_M;
    const plant_kinematics pk = plant_kinematics_of(&fw_geometry_of(s.fw)->p);
    if (plant_init(&s.plant, &pc, &pk, starts) != 0) {
        fprintf(stderr, "tse-sim: the kinematics refuses the controller's own geometry for the plant\n");
        return 1;
    }
    s.last_state = FW_STATE_BOOT;
    estop_watch_init(&s.estop);

    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    printf("tse-sim: node %ld on %s, %u Hz control, %u Hz steps\n", node, iface, rates.segment_hz, rates.step_hz);
    if (fault)
        printf("tse-sim: injecting faults: %s\n", fault);
    fflush(stdout);
    const posix_ticker_config tc = {rates.segment_hz, rates.step_hz, control, step, &s, LATE_WAIT_US, can.fd};
    const int rc = posix_ticker_start(&ticker, &tc);
    /* This thread is the controller's: frames as they come, and the periodic frames every
     * millisecond at least.  fw_poll takes every frame the bus holds, so after it the thread has
     * caught up with the bus as it was when the poll began (a late period waits for that). */
    while (rc == 0 && !quit && !fw_boot_requested(s.fw)) {
        const uint64_t look = posix_ticker_now_ns();
        fw_poll(s.fw);
        posix_ticker_caught_up(&ticker, look);
        posix_ticker_thread_wait(&ticker, can.fd, 1);
    }
    posix_ticker_stop(&ticker);
    posix_can_close(&can);
    if (fw_boot_requested(s.fw))
        /* A board restarts into its bootloader here; tse-boot-sim --stay is the simulator's. */
        printf("tse-sim: BOOT_ENTER taken: restarting into the bootloader (tse-boot-sim --stay takes over)\n");
    log_fault_counts(&s);
    /* Late periods: the host did not schedule tse-sim in time (a loaded machine, a VM).  The ticker
     * makes them up as soon as this thread has taken the frames that came before each, and the
     * plant's clock is the step count, so the simulated motion is exact; only frames in and out
     * were that much later than on a board. */
    printf("tse-sim: stopped after %llu control periods (%.1f s), %llu pulses\n", (unsigned long long)ticker.periods,
           (double)ticker.periods / rates.segment_hz, (unsigned long long)s.plant.pulses);
    if (ticker.overruns)
        printf("tse-sim: %llu of them (%.1f%%) ran late: the host scheduled tse-sim up to %.0f ms behind its %u Hz "
               "tick (a busy machine or a VM); they were made up once the frames that came before each were taken "
               "(%llu waited for the controller's thread, %llu of those to the %.0f ms bound), so the simulated motion "
               "is exact and only its CAN frames were that much later than a board's\n",
               (unsigned long long)ticker.overruns, 100.0 * (double)ticker.overruns / (double)ticker.periods,
               (double)ticker.max_behind * 1000.0 / rates.segment_hz, rates.segment_hz, (unsigned long long)ticker.late_waits,
               (unsigned long long)ticker.late_timeouts, LATE_WAIT_US / 1000.0);
    else
        printf("tse-sim: none of them ran late\n");
    return rc == 0 ? 0 : 1;
}
