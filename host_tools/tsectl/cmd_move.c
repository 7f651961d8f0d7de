/* move X Y Z ROLL PITCH YAW [--duration S | --speed V] [--wait] */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "commands.h"
#include "move_text.h"
#include "text.h"
#include "traj_file.h" /* the wire's pose range */

typedef struct {
    double p[6];
    int kind, wait;
    int32_t raw; /* ms or um/s, as MOVE_COMMIT carries it */
} move_args;

static const char *const axis[6] = {"X", "Y", "Z", "ROLL", "PITCH", "YAW"};

/* Checks a move's arguments; nothing is sent for a bad one. */
static int parse_move(int argc, char **argv, move_args *a)
{
    double value = 2.0;
    int timed = 0; /* --duration or --speed given */
    a->kind = 0;
    a->wait = 0;
    int npos = 0;
    for (int i = 0; i < argc; ++i) {
        if (!strcmp(argv[i], "--wait")) {
            a->wait = 1;
        } else if (!strcmp(argv[i], "--duration") || !strcmp(argv[i], "--speed")) {
            if (timed)
                return usage_error("move", "give --duration or --speed, not both", argv[i]);
            timed = 1;
            a->kind = argv[i][2] == 's';
            if (i + 1 >= argc)
                return usage_error("move", a->kind ? "--speed needs a plate speed in m/s" : "--duration needs seconds", NULL);
            if (text_number(argv[++i], &value) != 0 || !(value > 0))
                return usage_error("move", a->kind ? "--speed takes a positive speed in m/s" : "--duration takes positive seconds",
                                   argv[i]);
        } else if (npos < 6) {
            if (text_number(argv[i], &a->p[npos]) != 0) {
                char what[64];
                snprintf(what, sizeof what, "%s is not a number", axis[npos]);
                return usage_error("move", what, argv[i]);
            }
            const double lim = npos < 3 ? TRAJ_FILE_POS_MAX : TRAJ_FILE_ANGLE_MAX;
            if (fabs(a->p[npos]) > lim) {
                char what[96];
                snprintf(what, sizeof what, "%s is outside the wire's range -%g..%g %s", axis[npos], lim, lim,
                         npos < 3 ? "m" : "rad");
                return usage_error("move", what, argv[i]);
            }
            ++npos;
        } else {
            return usage_error("move", "unexpected argument", argv[i]);
        }
    }
    if (npos < 6)
        return usage_error("move", "needs X Y Z (m) ROLL PITCH YAW (rad)", NULL);
    /* MOVE_COMMIT's value: a speed in um/s or a duration in ms, 1 to PROTO_MOVE_VALUE_MAX. */
    const double per = a->kind ? PROTO_UM_PER_M : PROTO_MS_PER_S;
    const double raw = value * per;
    if (!(raw >= 1 && raw <= PROTO_MOVE_VALUE_MAX)) {
        char v[32], what[80];
        snprintf(v, sizeof v, "%g", value);
        snprintf(what, sizeof what, "%s must be %g to %g %s", a->kind ? "--speed" : "--duration", 1.0 / per,
                 PROTO_MOVE_VALUE_MAX / per, a->kind ? "m/s" : "s");
        return usage_error("move", what, v);
    }
    a->raw = (int32_t)lround(raw);
    return EXIT_OK;
}

/* The MOVE_INFO that follows a move's ACK, in words (nothing from a controller that sends none). */
static const char *info_words(tlink *l, int seq)
{
    static char text[256];
    text[0] = 0;
    const uint64_t end = link_now_us() + 300000u;
    proto_message m;
    while (link_now_us() < end && !tsectl_interrupted)
        if (link_recv(l, &m, 50) == 1 && m.msg == PM_MOVE_INFO && m.v[0] == seq)
            return move_info_text(&m, text, sizeof text);
    return text;
}

int check_move(int argc, char **argv, int *done)
{
    (void)done;
    move_args a;
    return parse_move(argc, argv, &a);
}

int run_move(tlink *l, int argc, char **argv)
{
    move_args a;
    if (parse_move(argc, argv, &a) != EXIT_OK)
        return EXIT_USAGE;
    const int seq = ctl_status_needed(l, NULL);
    if (seq < 0)
        return EXIT_TIMEOUT;
    const int32_t commit[3] = {seq, a.kind, a.raw};
    if (ctl_send_pose(l, seq, a.p) != 0 || link_send(l, PM_MOVE_COMMIT, commit) != 0) {
        ctl_error("cannot send on the bus");
        return EXIT_BUS;
    }
    proto_message ack, rej;
    int rc = ctl_answer(l, proto_table[PM_MOVE_COMMIT].function, seq, &ack, &rej);
    if (rc == EXIT_REJECTED)
        ctl_print_reject(&rej);
    if (rc == EXIT_OK) {
        const double T = (double)ack.v[4] / PROTO_MS_PER_S;
        printf("move accepted: %.3f s planned%s\n", T, info_words(l, seq));
        rc = a.wait ? ctl_wait_rest(l, T, "moving", 1, NULL) : EXIT_OK;
    }
    /* Interrupted while waiting (for the answer too: the move may have been taken). */
    if (rc == EXIT_INTERRUPTED)
        ctl_halt(l, "interrupted");
    return rc;
}
