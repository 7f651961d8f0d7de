/* tse-sim: the controller firmware on Linux SocketCAN, driving a simulated plant.
 *
 *   tse-sim --iface vcan0 --node N [--params FILE] [--start S]
 *
 * The firmware runs unchanged on hal/posix: a 1 kHz control tick from timerfd, each followed by
 * its 200 step interrupts against the plant (whose clock is the step count, so the simulated
 * physics is exact whatever the scheduler does).  State changes, faults and plant breaches are
 * logged on stdout; SIGINT or SIGTERM stops it cleanly. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "fw/controller.h"
#include "hal_posix/plant.h"
#include "hal_posix/posix_hal.h"

#define CONTROL_HZ 1000u
#define STEP_HZ 200000u

static posix_ticker ticker;

static void on_signal(int sig)
{
    (void)sig;
    ticker.stop = 1;
}

typedef struct {
    fw_controller fw;
    tse_plant plant;
    fw_state last_state;
    fw_fault last_fault;
    uint32_t reported;
    bool awaiting_first_step;
    uint64_t accepted_tick;   /* plant tick at which motion was accepted */
    uint64_t estop_tick;      /* plant tick at which the e-stop was taken (0: none) */
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

static void control(void *arg)
{
    sim *s = arg;
    fw_poll(&s->fw);
    fw_control_tick(&s->fw);
    if (s->plant.breaches & ~s->reported) {
        printf("tse-sim: plant: %s (breaches 0x%x)\n", s->plant.first_breach, s->plant.breaches);
        s->reported = s->plant.breaches;
        fw_report_fault(&s->fw, FW_FAULT_PLANT);
    }
    if (s->awaiting_first_step && s->plant.first_after_mark) {
        printf("tse-sim: first step %.3f ms after the command was taken\n",
               (double)(s->plant.first_after_mark - s->accepted_tick) * 1e3 / STEP_HZ);
        s->awaiting_first_step = false;
    }
    if (s->estop_tick && s->plant.last_pulse_tick > s->estop_tick) {
        printf("tse-sim: a step %.3f ms after the e-stop\n", (double)(s->plant.last_pulse_tick - s->estop_tick) * 1e3 / STEP_HZ);
        s->estop_tick = s->plant.last_pulse_tick;
    }
    if (s->fw.state != s->last_state || s->fw.fault != s->last_fault) {
        if (s->fw.state == FW_STATE_MOVING || s->fw.state == FW_STATE_HOMING) {
            s->awaiting_first_step = true;
            s->accepted_tick = s->plant.tick;
            plant_mark(&s->plant);
            printf("tse-sim: motion accepted at t = %.3f s\n", (double)s->plant.tick / STEP_HZ);
        }
        if (s->fw.state == FW_STATE_ESTOP && s->last_state != FW_STATE_ESTOP) {
            s->estop_tick = s->plant.tick;
            printf("tse-sim: e-stop taken; the last step was %.3f ms before it\n",
                   (double)(s->plant.tick - s->plant.last_pulse_tick) * 1e3 / STEP_HZ);
        }
        printf("tse-sim: state %s, fault %s\n", name_of(proto_state_names, s->fw.state),
               name_of(proto_fault_names, s->fw.fault));
        if (s->fw.state == FW_STATE_IDLE && s->fw.homed)
            log_pose(s, "at rest");
        s->last_state = s->fw.state;
        s->last_fault = s->fw.fault;
    }
    fflush(stdout);
}

static void step(void *arg)
{
    sim *s = arg;
    fw_step_tick(&s->fw);
    plant_tick(&s->plant);
}

static int usage(const char *why)
{
    fprintf(stderr, "tse-sim: %s\nusage: tse-sim --iface IFACE --node N [--params FILE] [--start S]\n"
                    "  --params FILE  where the controller keeps its parameters (PARAM_SAVE)\n"
                    "  --start S      slide positions at power-up [m] (default 0.05: below the homing\n"
                    "                 switches at 0.2 m, so homing first leaves them)\n", why);
    return 2;
}

int main(int argc, char **argv)
{
    const char *iface = NULL, *params = NULL;
    long node = -1;
    double start = 0.05;
    for (int i = 1; i < argc; ++i) {
        const int v = i + 1 < argc;
        char *end = NULL;
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            usage("simulated TSE controller on SocketCAN");
            return 0;
        } else if (!strcmp(argv[i], "--iface") && v) {
            iface = argv[++i];
        } else if (!strcmp(argv[i], "--node") && v) {
            node = strtol(argv[++i], &end, 10);
            if (*end || node < 1 || node > 15)
                return usage("--node takes 1..15");
        } else if (!strcmp(argv[i], "--params") && v) {
            params = argv[++i];
        } else if (!strcmp(argv[i], "--start") && v) {
            start = strtod(argv[++i], &end);
            if (*end || !(start > -0.01 && start < 0.91))
                return usage("--start takes a slide position in metres inside the stroke");
        } else {
            fprintf(stderr, "tse-sim: unexpected argument '%s'\n", argv[i]);
            return usage("bad arguments");
        }
    }
    if (!iface || node < 0)
        return usage("--iface and --node are needed");

    static sim s;
    static posix_can can;
    if (posix_can_open(&can, iface, (uint8_t)node) != 0) {
        fprintf(stderr, "tse-sim: cannot open CAN interface %s: %s\n", iface, strerror(errno));
        return 1;
    }
    posix_storage storage = {params};
    fw_hal hal;
    hal.can = posix_can_hal(&can);
    hal.stepper = plant_stepper(&s.plant);
    hal.inputs = plant_inputs(&s.plant);
    hal.clock = posix_clock_hal();
    hal.storage = posix_storage_hal(&storage);
    const fw_config cfg = {(uint8_t)node, CONTROL_HZ, STEP_HZ, false};
    if (fw_init(&s.fw, &hal, &cfg) != 0) {
        fprintf(stderr, "tse-sim: the controller did not start\n");
        return 1;
    }
    /* The plant follows the controller's parameters (stroke, steps per metre, limits, where the
     * homing switches sit, the drivers' timing the controller programmed in fw_init). */
    const double starts[6] = {start, start, start, start, start, start};
    const fw_param_set *fp = &s.fw.params;
    plant_config pc = {(double)fp->v[FP_STEPS_PER_M], (double)fp->v[FP_SLIDE_VMAX] * 1e-6,
                       (double)fp->v[FP_SLIDE_AMAX] * 1e-6, 0.05, STEP_HZ, s.fw.sg.cfg.min_step_interval,
                       (uint32_t)fp->v[FP_STEP_PULSE_NS], (uint32_t)fp->v[FP_DIR_SETUP_NS], {0}};
    for (int k = 0; k < 6; ++k)
        pc.home_sw[k] = (double)fp->v[FP_HOME_SW_1 + k] * 1e-6;
    plant_init(&s.plant, &pc, &s.fw.geom, starts);
    s.last_state = FW_STATE_BOOT;

    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    printf("tse-sim: node %ld on %s, %u Hz control, %u Hz steps\n", node, iface, CONTROL_HZ, STEP_HZ);
    fflush(stdout);
    hal_ticker t = posix_ticker_hal(&ticker);
    const int rc = t.start(t.ctx, CONTROL_HZ, control, STEP_HZ, step, &s);
    posix_can_close(&can);
    printf("tse-sim: stopped (%llu late periods, %llu pulses)\n", (unsigned long long)ticker.overruns,
           (unsigned long long)s.plant.pulses);
    return rc == 0 ? 0 : 1;
}
