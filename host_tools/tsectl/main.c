/* tsectl: command a TSE controller over SocketCAN.
 *
 *   tsectl --iface IF --node N COMMAND [args]
 *
 * Every command waits for the controller's ACK or REJECT (sending host heartbeats meanwhile)
 * and exits 0 on acknowledgement, 3 with the reason on a reject, 4 on a timeout, 1 when the bus
 * cannot be used, 2 for a usage error.  What it sends is plain protocol (docs/protocol.md), so
 * candump shows it and the DBC decodes it. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "fw/params.h"
#include "link.h"

enum { EXIT_OK = 0, EXIT_BUS = 1, EXIT_USAGE = 2, EXIT_REJECTED = 3, EXIT_TIMEOUT = 4 };

static volatile sig_atomic_t interrupted;
static void on_signal(int s)
{
    (void)s;
    interrupted = 1;
}

static int timeout_ms = 2000;

static const char *const usage_text =
    "usage: tsectl --iface IF --node N [--timeout MS] COMMAND [args]\n"
    "\n"
    "commands:\n"
    "  enable | disable | home [--wait] | clear | stop | estop\n"
    "  move X Y Z ROLL PITCH YAW [--duration S | --speed V] [--wait]   (metres, radians)\n"
    "  status [--json]          one STATUS of the controller\n"
    "  watch [--count N]        live telemetry: state, slides, plate pose\n"
    "  params list | get NAME | set NAME VALUE | save\n"
    "  trajectory FILE          CSV rows t,x,y,z,roll,pitch,yaw (t in s, increasing), streamed\n"
    "                           with flow control and a progress bar\n"
    "  heartbeat                host heartbeat every 100 ms until interrupted\n"
    "\n"
    "exit status: 0 acknowledged, 1 bus error, 2 usage, 3 rejected, 4 no answer in time\n";

static int usage_error(const char *what, const char *arg)
{
    fprintf(stderr, "tsectl: %s%s%s\n(try 'tsectl --help')\n", what, arg ? ": " : "", arg ? arg : "");
    return EXIT_USAGE;
}

static int function_of(proto_msg m)
{
    return proto_table[m].function;
}

/* The controller's last accepted commit, from its STATUS: a new sequence number must be newer. */
static int next_seq(tlink *l, proto_message *status)
{
    proto_message m;
    const uint64_t end = link_now_us() + (uint64_t)timeout_ms * 1000u;
    while (link_now_us() < end) {
        if (link_recv(l, &m, 100) == 1 && m.msg == PM_STATUS) {
            if (status)
                *status = m;
            return (uint8_t)(m.v[5] + 1);
        }
    }
    return -1;
}

static void print_reject(const proto_message *m)
{
    fprintf(stderr, "tsectl: rejected: %s", proto_enum_name(proto_reason_names, m->v[2]));
    if (m->v[2] == FW_REASON_KINEMATICS)
        fprintf(stderr, " (scissor %d, %s, at %.1f%% of the path)", (int)m->v[3],
                proto_enum_name(proto_kin_status_names, m->v[4]), m->v[6] / 10.0);
    if (m->v[2] == FW_REASON_RANGE)
        fprintf(stderr, " (field %d)", (int)m->v[5]);
    fprintf(stderr, "\n");
}

/* Waits for the ACK or REJECT of (function, seq).  Returns an exit status; *ack on acceptance. */
static int wait_answer(tlink *l, int function, int seq, proto_message *ack)
{
    const uint64_t end = link_now_us() + (uint64_t)timeout_ms * 1000u;
    proto_message m;
    while (link_now_us() < end && !interrupted) {
        if (link_recv(l, &m, 50) != 1)
            continue;
        if ((m.msg == PM_ACK || m.msg == PM_REJECT) && m.v[0] == function && (seq < 0 || m.v[1] == seq)) {
            if (m.msg == PM_REJECT) {
                print_reject(&m);
                return EXIT_REJECTED;
            }
            if (ack)
                *ack = m;
            return EXIT_OK;
        }
    }
    fprintf(stderr, "tsectl: no answer from node %u within %d ms\n", l->node, timeout_ms);
    return EXIT_TIMEOUT;
}

static int simple(tlink *l, proto_msg msg)
{
    const int seq = next_seq(l, NULL);
    if (seq < 0)
        return fprintf(stderr, "tsectl: no STATUS from node %u\n", l->node), EXIT_TIMEOUT;
    const int32_t v[1] = {seq};
    if (link_send(l, msg, v) != 0)
        return perror("tsectl: send"), EXIT_BUS;
    const int rc = wait_answer(l, function_of(msg), seq, NULL);
    if (rc == EXIT_OK)
        printf("%s: acknowledged\n", proto_table[msg].name);
    return rc;
}

static void progress(double frac, const char *what)
{
    const int width = 40, n = (int)(frac * width + 0.5);
    printf("\r%-10s [", what);
    for (int i = 0; i < width; ++i)
        putchar(i < n ? '#' : '.');
    printf("] %3d%%", (int)(frac * 100 + 0.5));
    fflush(stdout);
}

/* Follows STATUS until the controller is at rest (idle, fault, estop). */
static int wait_rest(tlink *l, double expected_s, const char *what)
{
    const uint64_t t0 = link_now_us();
    /* Bounded: three times what was planned plus a minute (homing has no plan). */
    const double limit = 3.0 * (expected_s > 0 ? expected_s : 60.0) + 60.0;
    proto_message m;
    int seen_motion = 0;
    for (;;) {
        if (interrupted || (double)(link_now_us() - t0) * 1e-6 > limit) {
            fprintf(stderr, "\ntsectl: %s did not come to rest in time\n", what);
            return EXIT_TIMEOUT;
        }
        if (link_recv(l, &m, 200) != 1 || m.msg != PM_STATUS)
            continue;
        const int st = m.v[0];
        const double el = (double)(link_now_us() - t0) * 1e-6;
        if (st == FW_STATE_MOVING || st == FW_STATE_HOMING || st == FW_STATE_STOPPING)
            seen_motion = 1;
        progress(expected_s > 0 ? fmin(el / expected_s, 0.99) : fmin(el / (el + 5.0), 0.99), what);
        if (seen_motion && (st == FW_STATE_IDLE || st == FW_STATE_FAULT || st == FW_STATE_ESTOP)) {
            progress(st == FW_STATE_IDLE ? 1.0 : el / (expected_s > 0 ? expected_s : el), what);
            printf("\n%s: %s after %.2f s, fault %s\n", what, proto_enum_name(proto_state_names, st), el,
                   proto_enum_name(proto_fault_names, m.v[1]));
            return st == FW_STATE_IDLE && m.v[1] == FW_FAULT_NONE ? EXIT_OK : EXIT_REJECTED;
        }
        if (!seen_motion && el > 2.0 && st == FW_STATE_IDLE) {
            printf("\n%s: already at rest\n", what);
            return EXIT_OK;
        }
    }
}

static int stage(tlink *l, int seq, const double p[6])
{
    const int32_t a[3] = {seq, (int32_t)lround(p[0] * 1e6), (int32_t)lround(p[1] * 1e6)};
    const int32_t b[3] = {seq, (int32_t)lround(p[2] * 1e6), (int32_t)lround(p[3] * 1e6)};
    const int32_t c[3] = {seq, (int32_t)lround(p[4] * 1e6), (int32_t)lround(p[5] * 1e6)};
    return link_send(l, PM_POSE_A, a) || link_send(l, PM_POSE_B, b) || link_send(l, PM_POSE_C, c) ? -1 : 0;
}

static int parse_number(const char *s, double *out)
{
    char *end;
    errno = 0;
    *out = strtod(s, &end);
    return *s && !*end && errno == 0 && isfinite(*out) ? 0 : -1;
}

typedef struct {
    double p[6];
    int kind, wait;
    int32_t raw; /* ms or um/s */
} move_args;

/* Checks a move's arguments; nothing is sent for a bad one. */
static int parse_move(int argc, char **argv, move_args *a)
{
    double value = 2.0;
    a->kind = 0;
    a->wait = 0;
    if (argc < 6)
        return usage_error("move needs X Y Z ROLL PITCH YAW", NULL);
    for (int i = 0; i < 6; ++i)
        if (parse_number(argv[i], &a->p[i]) != 0)
            return usage_error("not a number", argv[i]);
    for (int i = 6; i < argc; ++i) {
        if (!strcmp(argv[i], "--wait")) {
            a->wait = 1;
        } else if ((!strcmp(argv[i], "--duration") || !strcmp(argv[i], "--speed")) && i + 1 < argc) {
            a->kind = argv[i][2] == 's';
            if (parse_number(argv[++i], &value) != 0 || !(value > 0))
                return usage_error("--duration and --speed take a positive number", argv[i]);
        } else {
            return usage_error("unexpected argument", argv[i]);
        }
    }
    const double raw = a->kind ? value * 1e6 : value * 1e3;
    if (raw < 1 || raw > 3600000)
        return usage_error("--duration must be 1 ms to 1 h, --speed 1 um/s to 3.6 m/s", NULL);
    a->raw = (int32_t)lround(raw);
    for (int i = 0; i < 6; ++i)
        if (fabs(a->p[i]) > (i < 3 ? 4.0 : 3.141593))
            return usage_error("a pose outside the wire's range (+-4 m, +-pi rad)", argv[i]);
    return EXIT_OK;
}

static int cmd_move(tlink *l, const move_args *a)
{
    const int seq = next_seq(l, NULL);
    if (seq < 0)
        return fprintf(stderr, "tsectl: no STATUS from node %u\n", l->node), EXIT_TIMEOUT;
    const int32_t commit[3] = {seq, a->kind, a->raw};
    if (stage(l, seq, a->p) != 0 || link_send(l, PM_MOVE_COMMIT, commit) != 0)
        return perror("tsectl: send"), EXIT_BUS;
    proto_message ack;
    const int rc = wait_answer(l, function_of(PM_MOVE_COMMIT), seq, &ack);
    if (rc != EXIT_OK)
        return rc;
    const double T = ack.v[4] * 1e-3;
    printf("move accepted: %.3f s planned\n", T);
    return a->wait ? wait_rest(l, T, "moving") : EXIT_OK;
}

static int cmd_home(tlink *l, int argc, char **argv)
{
    const int wait = argc > 0 && !strcmp(argv[0], "--wait");
    const int rc = simple(l, PM_HOME);
    return rc == EXIT_OK && wait ? wait_rest(l, 0, "homing") : rc;
}

static void print_status(const proto_message *m, int json)
{
    const int fl = m->v[2];
    if (json)
        printf("{\"state\": \"%s\", \"fault\": \"%s\", \"homed\": %s, \"enabled\": %s, \"estop_input\": %s, "
               "\"limit\": %s, \"queue_depth\": %d, \"queue_free\": %d, \"last_seq\": %d, \"counter\": %d}\n",
               proto_enum_name(proto_state_names, m->v[0]), proto_enum_name(proto_fault_names, m->v[1]),
               fl & 1 ? "true" : "false", fl & 2 ? "true" : "false", fl & 4 ? "true" : "false",
               fl & 8 ? "true" : "false", (int)m->v[3], (int)m->v[4], (int)m->v[5], (int)m->v[6]);
    else
        printf("state %s, fault %s, %s, drives %s, queue %d (free %d), last seq %d\n",
               proto_enum_name(proto_state_names, m->v[0]), proto_enum_name(proto_fault_names, m->v[1]),
               fl & 1 ? "homed" : "not homed", fl & 2 ? "on" : "off", (int)m->v[3], (int)m->v[4], (int)m->v[5]);
}

static int cmd_status(tlink *l, int argc, char **argv)
{
    proto_message st;
    if (next_seq(l, &st) < 0)
        return fprintf(stderr, "tsectl: no STATUS from node %u\n", l->node), EXIT_TIMEOUT;
    print_status(&st, argc > 0 && !strcmp(argv[0], "--json"));
    return EXIT_OK;
}

static int cmd_watch(tlink *l, int argc, char **argv)
{
    long count = -1;
    if (argc >= 2 && !strcmp(argv[0], "--count"))
        count = strtol(argv[1], NULL, 10);
    int32_t fk[6] = {0}, sl[6] = {0};
    while (!interrupted && count != 0) {
        proto_message m;
        if (link_recv(l, &m, 500) != 1)
            continue;
        if (m.msg >= PM_SLIDES_A && m.msg <= PM_SLIDES_C) {
            sl[2 * (m.msg - PM_SLIDES_A)] = m.v[0];
            sl[2 * (m.msg - PM_SLIDES_A) + 1] = m.v[1];
        } else if (m.msg >= PM_FK_A && m.msg <= PM_FK_C) {
            fk[2 * (m.msg - PM_FK_A)] = m.v[0];
            fk[2 * (m.msg - PM_FK_A) + 1] = m.v[1];
            if (m.msg == PM_FK_C)
                printf("pose %.6f %.6f %.6f m %.6f %.6f %.6f rad | slides %.4f %.4f %.4f %.4f %.4f %.4f m\n",
                       fk[0] * 1e-6, fk[1] * 1e-6, fk[2] * 1e-6, fk[3] * 1e-6, fk[4] * 1e-6, fk[5] * 1e-6,
                       sl[0] * 1e-9, sl[1] * 1e-9, sl[2] * 1e-9, sl[3] * 1e-9, sl[4] * 1e-9, sl[5] * 1e-9);
        } else if (m.msg == PM_STATUS) {
            print_status(&m, 0);
            if (count > 0)
                --count;
        }
        fflush(stdout);
    }
    return EXIT_OK;
}

static int param_id(const char *s)
{
    for (int i = 0; i < FP_COUNT; ++i)
        if (!strcasecmp(s, fw_param_table[i].name))
            return i;
    char *end;
    const long v = strtol(s, &end, 10);
    return *s && !*end && v >= 0 && v < FP_COUNT ? (int)v : -1;
}

static int cmd_params(tlink *l, int argc, char **argv)
{
    if (argc < 1)
        return usage_error("params needs list, get, set or save", NULL);
    if (!strcmp(argv[0], "list")) {
        for (int i = 0; i < FP_COUNT; ++i)
            printf("%2d %-16s %-9s [%ld, %ld] default %ld  %s\n", i, fw_param_table[i].name, fw_param_table[i].unit,
                   (long)fw_param_table[i].min, (long)fw_param_table[i].max, (long)fw_param_table[i].def,
                   fw_param_table[i].doc);
        return EXIT_OK;
    }
    if (!strcmp(argv[0], "save")) {
        const int32_t v[1] = {0x45564153};
        link_send(l, PM_PARAM_SAVE, v);
        const int rc = wait_answer(l, function_of(PM_PARAM_SAVE), -1, NULL);
        if (rc == EXIT_OK)
            printf("parameters saved\n");
        return rc;
    }
    const int get = !strcmp(argv[0], "get"), set = !strcmp(argv[0], "set");
    if ((!get && !set) || argc < (set ? 3 : 2))
        return usage_error("params get NAME | params set NAME VALUE", NULL);
    const int id = param_id(argv[1]);
    if (id < 0)
        return usage_error("unknown parameter (see 'tsectl params list')", argv[1]);
    int32_t v[2] = {id, 0};
    if (set) {
        char *end;
        errno = 0;
        const long x = strtol(argv[2], &end, 10);
        if (!*argv[2] || *end || errno || x < fw_param_table[id].min || x > fw_param_table[id].max)
            return usage_error("the value must be a whole number in the parameter's range", argv[2]);
        v[1] = (int32_t)x;
    }
    link_send(l, set ? PM_PARAM_SET : PM_PARAM_GET, v);
    const int rc = wait_answer(l, function_of(set ? PM_PARAM_SET : PM_PARAM_GET), -1, NULL);
    if (rc != EXIT_OK)
        return rc;
    proto_message m;
    const uint64_t end = link_now_us() + (uint64_t)timeout_ms * 1000u;
    while (link_now_us() < end)
        if (link_recv(l, &m, 50) == 1 && m.msg == PM_PARAM_VALUE && m.v[0] == id) {
            printf("%s = %ld %s\n", fw_param_table[id].name, (long)m.v[1], fw_param_table[id].unit);
            return EXIT_OK;
        }
    return EXIT_TIMEOUT;
}

typedef struct {
    double t, p[6];
} traj_row;

/* Reads and checks the whole file before anything is sent: a bad row names its line. */
static traj_row *read_trajectory(const char *path, int *n)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        fprintf(stderr, "tsectl: %s: %s\n", path, strerror(errno));
        return NULL;
    }
    int cap = 1024, count = 0, line = 0;
    traj_row *rows = malloc(sizeof *rows * (size_t)cap);
    char buf[1024];
    double prev = 0.0;
    while (rows && fgets(buf, sizeof buf, f)) {
        ++line;
        char *s = buf;
        while (*s == ' ' || *s == '\t')
            ++s;
        if (*s == '#' || *s == '\n' || *s == '\r' || *s == '\0' || (line == 1 && strchr("tT", *s)))
            continue; /* comments, blank lines, a header */
        double v[7];
        int k = 0;
        char *tok = strtok(s, ",\r\n");
        while (tok && k < 8) {
            if (k < 7 && parse_number(tok, &v[k]) != 0) {
                fprintf(stderr, "tsectl: %s:%d: field %d '%s' is not a number\n", path, line, k + 1, tok);
                free(rows);
                rows = NULL;
                break;
            }
            ++k;
            tok = strtok(NULL, ",\r\n");
        }
        if (!rows)
            break;
        if (k != 7) {
            fprintf(stderr, "tsectl: %s:%d: expected 7 fields t,x,y,z,roll,pitch,yaw, got %d\n", path, line, k);
            free(rows);
            rows = NULL;
            break;
        }
        if (!(v[0] > prev) || v[0] - prev > 60.0 || (v[0] - prev) < 1e-3) {
            fprintf(stderr, "tsectl: %s:%d: t must increase by 1 ms to 60 s per row (%g after %g)\n", path, line, v[0], prev);
            free(rows);
            rows = NULL;
            break;
        }
        if (count == cap) {
            cap *= 2;
            traj_row *r = realloc(rows, sizeof *rows * (size_t)cap);
            if (!r) {
                free(rows);
                rows = NULL;
                break;
            }
            rows = r;
        }
        rows[count].t = v[0];
        memcpy(rows[count].p, &v[1], sizeof rows[count].p);
        prev = v[0];
        ++count;
    }
    fclose(f);
    if (rows && count == 0) {
        fprintf(stderr, "tsectl: %s: no trajectory rows\n", path);
        free(rows);
        rows = NULL;
    }
    *n = count;
    return rows;
}

static int cmd_trajectory(tlink *l, int argc, char **argv)
{
    if (argc < 1)
        return usage_error("trajectory needs a CSV file", NULL);
    int n = 0;
    traj_row *rows = read_trajectory(argv[0], &n);
    if (!rows)
        return EXIT_USAGE;
    proto_message st;
    int seq = next_seq(l, &st);
    if (seq < 0) {
        free(rows);
        return fprintf(stderr, "tsectl: no STATUS from node %u\n", l->node), EXIT_TIMEOUT;
    }
    int free_slots = (int)st.v[4], acked = 0, rc = EXIT_OK;
    double prev_t = 0.0;
    const uint64_t t0 = link_now_us();
    for (int i = 0; i < n && rc == EXIT_OK && !interrupted; ++i) {
        /* Flow control: wait for room, as the controller reports it. */
        while (free_slots <= 0 && !interrupted) {
            proto_message m;
            if (link_recv(l, &m, 100) == 1 && m.msg == PM_STATUS) {
                free_slots = (int)m.v[4];
                if (m.v[0] == FW_STATE_FAULT || m.v[0] == FW_STATE_ESTOP) {
                    fprintf(stderr, "\ntsectl: the controller stopped: %s\n", proto_enum_name(proto_fault_names, m.v[1]));
                    rc = EXIT_REJECTED;
                    break;
                }
            }
        }
        if (rc != EXIT_OK)
            break;
        const int s = (uint8_t)seq;
        const int32_t commit[3] = {s, (int32_t)lround((rows[i].t - prev_t) * 1e6), i == n - 1};
        if (stage(l, s, rows[i].p) != 0 || link_send(l, PM_TRAJ_COMMIT, commit) != 0) {
            fprintf(stderr, "\ntsectl: row %d: a pose outside the wire's range or a send error\n", i + 1);
            rc = EXIT_USAGE;
            break;
        }
        proto_message ack;
        rc = wait_answer(l, function_of(PM_TRAJ_COMMIT), s, &ack);
        if (rc == EXIT_OK) {
            free_slots = (int)ack.v[3];
            ++acked;
            progress((double)acked / n, "streaming");
        } else {
            fprintf(stderr, "tsectl: point %d (t = %g s) was refused\n", i + 1, rows[i].t);
        }
        prev_t = rows[i].t;
        seq = (uint8_t)(seq + 1);
    }
    if (rc == EXIT_OK) {
        printf("\n%d points streamed in %.2f s\n", acked, (double)(link_now_us() - t0) * 1e-6);
        rc = wait_rest(l, rows[n - 1].t - (double)(link_now_us() - t0) * 1e-6, "finishing");
    }
    free(rows);
    return rc;
}

static int cmd_heartbeat(tlink *l)
{
    proto_message m;
    while (!interrupted)
        link_recv(l, &m, 200);
    (void)m;
    return EXIT_OK;
}

int main(int argc, char **argv)
{
    const char *iface = NULL;
    long node = -1;
    int i = 1;
    for (; i < argc; ++i) {
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            fputs(usage_text, stdout);
            return EXIT_OK;
        } else if (!strcmp(argv[i], "--iface") && i + 1 < argc) {
            iface = argv[++i];
        } else if (!strcmp(argv[i], "--node") && i + 1 < argc) {
            char *end;
            node = strtol(argv[++i], &end, 10);
            if (*end || node < 1 || node > 15)
                return usage_error("--node takes 1..15", argv[i]);
        } else if (!strcmp(argv[i], "--timeout") && i + 1 < argc) {
            char *end;
            timeout_ms = (int)strtol(argv[++i], &end, 10);
            if (*end || timeout_ms < 10 || timeout_ms > 600000)
                return usage_error("--timeout takes 10..600000 ms", argv[i]);
        } else if (argv[i][0] == '-') {
            return usage_error("unknown option", argv[i]);
        } else {
            break;
        }
    }
    if (i >= argc)
        return usage_error("a command is needed", NULL);
    if (!iface || node < 0)
        return usage_error("--iface and --node are needed", NULL);
    const char *cmd = argv[i];
    char **args = argv + i + 1;
    const int nargs = argc - i - 1;
    static const char *const known[] = {"enable", "disable", "home", "clear", "stop", "estop", "move", "status",
                                        "watch", "params", "trajectory", "heartbeat"};
    int ok = 0;
    for (size_t k = 0; k < sizeof known / sizeof known[0]; ++k)
        ok |= !strcmp(cmd, known[k]);
    if (!ok)
        return usage_error("unknown command", cmd);
    if (!strcmp(cmd, "params") && nargs > 0 && !strcmp(args[0], "list"))
        return cmd_params(NULL, nargs, args);
    move_args mv;
    if (!strcmp(cmd, "move")) {
        const int bad = parse_move(nargs, args, &mv);
        if (bad != EXIT_OK)
            return bad;
    }
    if (!strcmp(cmd, "trajectory")) {
        /* A bad file is reported before the bus is touched. */
        int n;
        traj_row *rows = nargs > 0 ? read_trajectory(args[0], &n) : NULL;
        if (!rows)
            return nargs > 0 ? EXIT_USAGE : usage_error("trajectory needs a CSV file", NULL);
        free(rows);
    }

    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    tlink l;
    if (link_open(&l, iface, (uint8_t)node) != 0) {
        fprintf(stderr, "tsectl: cannot open CAN interface %s: %s\n", iface, strerror(errno));
        return EXIT_BUS;
    }
    l.heartbeat = strcmp(cmd, "estop") != 0;
    int rc;
    if (!strcmp(cmd, "enable"))
        rc = simple(&l, PM_ENABLE);
    else if (!strcmp(cmd, "disable"))
        rc = simple(&l, PM_DISABLE);
    else if (!strcmp(cmd, "clear"))
        rc = simple(&l, PM_CLEAR_FAULT);
    else if (!strcmp(cmd, "stop"))
        rc = simple(&l, PM_STOP);
    else if (!strcmp(cmd, "estop")) {
        /* No waiting for a STATUS first: the e-stop goes out at once. */
        const int32_t v[1] = {0};
        rc = link_send(&l, PM_ESTOP, v) == 0 ? wait_answer(&l, function_of(PM_ESTOP), 0, NULL) : EXIT_BUS;
        if (rc == EXIT_OK)
            printf("ESTOP: acknowledged\n");
    } else if (!strcmp(cmd, "home"))
        rc = cmd_home(&l, nargs, args);
    else if (!strcmp(cmd, "move"))
        rc = cmd_move(&l, &mv);
    else if (!strcmp(cmd, "status"))
        rc = cmd_status(&l, nargs, args);
    else if (!strcmp(cmd, "watch"))
        rc = cmd_watch(&l, nargs, args);
    else if (!strcmp(cmd, "params"))
        rc = cmd_params(&l, nargs, args);
    else if (!strcmp(cmd, "trajectory"))
        rc = cmd_trajectory(&l, nargs, args);
    else
        rc = cmd_heartbeat(&l);
    link_close(&l);
    return rc;
}
