/* The one-frame commands: enable, disable, clear, stop, estop, home, and the heartbeat. */
#include <stdio.h>
#include <string.h>

#include "commands.h"

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

int run_enable(tlink *l, int argc, char **argv)
{
    (void)argc, (void)argv;
    return ctl_simple(l, PM_ENABLE, NULL);
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

int run_stop(tlink *l, int argc, char **argv)
{
    const int rc = ctl_simple(l, PM_STOP, NULL);
    return rc == EXIT_OK && argc > 0 && !strcmp(argv[0], "--wait") ? ctl_wait_rest(l, 0, "stopping", 0, NULL) : rc;
}

int run_estop(tlink *l, int argc, char **argv)
{
    (void)argc, (void)argv;
    /* No waiting for a STATUS first: the e-stop goes out at once. */
    const int32_t v[1] = {0};
    if (link_send(l, PM_ESTOP, v) != 0) {
        ctl_error("cannot send on the bus");
        return EXIT_BUS;
    }
    proto_message rej;
    const int rc = ctl_answer(l, proto_table[PM_ESTOP].function, 0, NULL, &rej);
    if (rc == EXIT_OK)
        printf("ESTOP: acknowledged\n");
    else if (rc == EXIT_REJECTED)
        ctl_print_reject(&rej);
    return rc;
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
            return ctl_wait_rest(l, 0, "homing", 1, NULL);
        }
        ctl_print_reject(&rej);
        return rc;
    }
    return rc == EXIT_OK && wait ? ctl_wait_rest(l, 0, "homing", 1, NULL) : rc;
}

int run_heartbeat(tlink *l, int argc, char **argv)
{
    (void)argc, (void)argv;
    proto_message m;
    while (!tsectl_interrupted)
        link_recv(l, &m, 200);
    return EXIT_OK;
}
