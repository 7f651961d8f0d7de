/* The one-frame commands: enable, disable, clear, stop, estop, home, and the heartbeat. */
#include <stdio.h>
#include <string.h>

#include "commands.h"
#include "ctl_params.h"

int check_none(int argc, char **argv, int *done)
{
    (void)done;
    return argc > 0 ? usage_error(NULL, "unexpected argument", argv[0]) : EXIT_OK;
}

int check_flags(int argc, char **argv, int *done)
{
    (void)done;
    for (int i = 0; i < argc; ++i)
        if (strcmp(argv[i], "--wait") != 0)
            return usage_error(NULL, "unexpected argument", argv[i]);
    return EXIT_OK;
}

/* With the drives on, the controller faults `watchdog` after watchdog_ms of host silence, and
 * this tsectl ends in a moment: say so when no other host keeps the heartbeat.  (Another host's
 * heartbeat comes every 100 ms: 300 ms without one is none.) */
static void warn_without_heartbeat(tlink *l)
{
    const uint64_t end = link_now_us() + 300000u;
    proto_message m;
    while (!l->other_heartbeat_us && link_now_us() < end && !tsectl_interrupted)
        link_recv(l, &m, 50);
    int32_t ms = 0;
    if (l->other_heartbeat_us || tsectl_interrupted || ctl_param_get(l, FP_WATCHDOG_MS, &ms) != EXIT_OK || ms == 0)
        return;
    ctl_error("warning: no host heartbeat on the bus: node %u will stop and fault 'watchdog' %d ms after this "
              "command ends; keep 'tsectl --iface IF --node %u heartbeat &' running while the drives are on",
              l->node, (int)ms, l->node);
}

int run_enable(tlink *l, int argc, char **argv)
{
    (void)argc, (void)argv;
    const int rc = ctl_simple(l, PM_ENABLE, NULL);
    if (rc == EXIT_OK)
        warn_without_heartbeat(l);
    return rc;
}

int run_disable(tlink *l, int argc, char **argv)
{
    (void)argc, (void)argv;
    return ctl_simple(l, PM_DISABLE, NULL);
}

int run_clear(tlink *l, int argc, char **argv)
{
    (void)argc, (void)argv;
    return ctl_simple(l, PM_CLEAR_FAULT, NULL);
}

/* A command whose motion runs while tsectl waits: an interrupt stops it (ctl_halt) and exits 130. */
static int halted(tlink *l, int rc)
{
    if (rc == EXIT_INTERRUPTED)
        ctl_halt(l, "interrupted");
    return rc;
}

int run_stop(tlink *l, int argc, char **argv)
{
    const int rc = ctl_simple(l, PM_STOP, NULL);
    return halted(l, rc == EXIT_OK && argc > 0 && !strcmp(argv[0], "--wait") ? ctl_wait_rest(l, 0, "stopping", 0, NULL)
                                                                             : rc);
}

int run_estop(tlink *l, int argc, char **argv)
{
    (void)argc, (void)argv;
    return ctl_estop(l);
}

int run_home(tlink *l, int argc, char **argv)
{
    const int wait = argc > 0 && !strcmp(argv[0], "--wait");
    proto_message rej;
    const int rc = ctl_simple(l, PM_HOME, &rej);
    if (rc == EXIT_REJECTED) {
        proto_message st;
        /* The controller names its state in the reject; an older one does not, STATUS does. */
        const int homing = rej.v[2] == FW_REASON_STATE &&
                           (rej.v[5] == FW_STATE_HOMING || (ctl_status(l, &st) >= 0 && st.v[0] == FW_STATE_HOMING));
        if (wait && homing) {
            printf("homing is already running: waiting for it\n");
            return halted(l, ctl_wait_rest(l, 0, "homing", 1, NULL));
        }
        ctl_print_reject(&rej);
        return rc;
    }
    /* Interrupted before the answer: the homing may have started all the same. */
    return halted(l, rc == EXIT_OK && wait ? ctl_wait_rest(l, 0, "homing", 1, NULL) : rc);
}

int run_heartbeat(tlink *l, int argc, char **argv)
{
    (void)argc, (void)argv;
    proto_message m;
    while (!tsectl_interrupted)
        link_recv(l, &m, 200);
    return EXIT_OK;
}
