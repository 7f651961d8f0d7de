/* status [--json]: one STATUS with the pose and slides; watch [--count N]: live telemetry; info
 * [--json]: the firmware's version and the controller's rates. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "ctl_info.h"
#include "telemetry.h"
#include "tse_version.h"

static void print_status(const proto_message *m, const telemetry *t, int json)
{
    const int fl = m->v[2];
    const char *st = proto_enum_name(proto_state_names, m->v[0]), *fault = proto_enum_name(proto_fault_names, m->v[1]);
    if (json) {
        printf("{\"state\": \"%s\", \"fault\": \"%s\", \"homed\": %s, \"enabled\": %s, \"estop_input\": %s, "
               "\"limit\": %s, \"queue_depth\": %d, \"queue_free\": %d, \"last_seq\": %d, \"counter\": %d",
               st, fault, fl & PROTO_STATUS_HOMED ? "true" : "false", fl & PROTO_STATUS_DRIVES ? "true" : "false",
               fl & PROTO_STATUS_ESTOP_IN ? "true" : "false", fl & PROTO_STATUS_SWITCHES_OFF ? "true" : "false",
               (int)m->v[3], (int)m->v[4], (int)m->v[5], (int)m->v[6]);
        if (t && telemetry_has_pose(t))
            printf(", \"pose\": [%.6f, %.6f, %.6f, %.6f, %.6f, %.6f]", t->pose[0], t->pose[1], t->pose[2], t->pose[3],
                   t->pose[4], t->pose[5]);
        else
            printf(", \"pose\": null");
        if (t && telemetry_has_slides(t))
            printf(", \"slides\": [%.9f, %.9f, %.9f, %.9f, %.9f, %.9f]", t->slides[0], t->slides[1], t->slides[2],
                   t->slides[3], t->slides[4], t->slides[5]);
        else
            printf(", \"slides\": null");
        printf("}\n");
        return;
    }
    printf("state %s, fault %s, %s, drives %s, queue %d (free %d), last seq %d%s%s\n", st, fault,
           fl & PROTO_STATUS_HOMED ? "homed" : "not homed", fl & PROTO_STATUS_DRIVES ? "on" : "off", (int)m->v[3],
           (int)m->v[4], (int)m->v[5], fl & PROTO_STATUS_ESTOP_IN ? ", e-stop input open" : "",
           fl & PROTO_STATUS_SWITCHES_OFF ? ", a switch disagrees" : "");
    if (!t)
        return;
    if (telemetry_has_pose(t))
        printf("pose %.6f %.6f %.6f m, %.6f %.6f %.6f rad\n", t->pose[0], t->pose[1], t->pose[2], t->pose[3],
               t->pose[4], t->pose[5]);
    else
        printf("pose unknown (%s)\n", fl & PROTO_STATUS_HOMED ? "no telemetry: telemetry_ms is 0?" : "not homed");
    if (telemetry_has_slides(t))
        printf("slides %.6f %.6f %.6f %.6f %.6f %.6f m\n", t->slides[0], t->slides[1], t->slides[2], t->slides[3],
               t->slides[4], t->slides[5]);
}

int check_json(int argc, char **argv, int *done)
{
    (void)done;
    if (argc > 1 || (argc == 1 && strcmp(argv[0], "--json") != 0))
        return usage_error(NULL, "unexpected argument", argv[argc > 1 && !strcmp(argv[0], "--json") ? 1 : 0]);
    return EXIT_OK;
}

int run_status(tlink *l, int argc, char **argv)
{
    (void)argv;
    proto_message st;
    if (ctl_status_needed(l, &st) < 0)
        return EXIT_TIMEOUT;
    /* The pose comes with the telemetry (every telemetry_ms, 50 ms by default); only once homed. */
    telemetry t;
    memset(&t, 0, sizeof t);
    const int homed = (st.v[2] & PROTO_STATUS_HOMED) != 0;
    const uint64_t end = link_now_us() + 500000u;
    proto_message m;
    if (link_telemetry(l, true) < 0)
        return ctl_error("cannot set the CAN socket's filter: %s", strerror(errno)), EXIT_BUS;
    while (link_now_us() < end && !tsectl_interrupted) {
        if (link_recv(l, &m, 50) == 1)
            telemetry_take(&t, &m);
        if (telemetry_has_slides(&t) && (!homed || telemetry_has_pose(&t)))
            break;
    }
    print_status(&st, &t, argc > 0);
    return EXIT_OK;
}

int check_watch(int argc, char **argv, int *done)
{
    (void)done;
    if (argc == 0)
        return EXIT_OK;
    char *end;
    if (argc == 2 && !strcmp(argv[0], "--count") && strtol(argv[1], &end, 10) > 0 && !*end)
        return EXIT_OK;
    return usage_error("watch", "takes only --count N (N > 0)", argv[0]);
}

int run_watch(tlink *l, int argc, char **argv)
{
    long count = argc == 2 ? strtol(argv[1], NULL, 10) : -1;
    telemetry t;
    memset(&t, 0, sizeof t);
    if (link_telemetry(l, true) < 0)
        return ctl_error("cannot set the CAN socket's filter: %s", strerror(errno)), EXIT_BUS;
    while (!tsectl_interrupted && count != 0) {
        proto_message m;
        if (link_recv(l, &m, 500) != 1)
            continue;
        if (telemetry_take(&t, &m))
            printf("pose %.6f %.6f %.6f m %.6f %.6f %.6f rad | slides %.4f %.4f %.4f %.4f %.4f %.4f m\n", t.pose[0],
                   t.pose[1], t.pose[2], t.pose[3], t.pose[4], t.pose[5], t.slides[0], t.slides[1], t.slides[2],
                   t.slides[3], t.slides[4], t.slides[5]);
        if (m.msg == PM_STATUS) {
            print_status(&m, NULL, 0);
            if (count > 0)
                --count;
        }
        fflush(stdout);
    }
    return EXIT_OK;
}

int run_info(tlink *l, int argc, char **argv)
{
    (void)argv;
    ctl_info info;
    bool older;
    const int rc = ctl_info_read(l, &info, &older);
    if (older)
        ctl_error("node %u does not know INFO_GET: a firmware older than INFO, which ran at the built-in rates "
                  "(%u Hz step interrupts, %u Hz control segments)",
                  l->node, FW_STEP_HZ, FW_SEGMENT_HZ);
    if (rc != EXIT_OK)
        return rc;
    if (argc > 0)
        printf("{\"version\": \"%d.%d.%d\", \"step_hz\": %u, \"segment_hz\": %u}\n", info.major, info.minor,
               info.patch, info.rates.step_hz, info.rates.segment_hz);
    else
        printf("node %u: firmware %d.%d.%d, %u Hz step interrupts, %u Hz control segments (tsectl %s)\n", l->node,
               info.major, info.minor, info.patch, info.rates.step_hz, info.rates.segment_hz, TSE_VERSION);
    return EXIT_OK;
}
