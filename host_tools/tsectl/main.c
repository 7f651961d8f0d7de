/* tsectl: command a TSE controller over SocketCAN.
 *
 *   tsectl --iface IF --node N [--timeout MS] COMMAND [args]
 *   tsectl [COMMAND] --help
 *
 * Every command waits for the controller's ACK or REJECT (sending host heartbeats meanwhile); a
 * REJECT is explained in words.  What it sends is plain protocol (docs/protocol.md), so candump
 * shows it and the DBC decodes it.  Exit statuses: tsectl.h. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "fw/limits.h"
#include "tse_version.h"

static void on_signal(int s)
{
    (void)s;
    tsectl_interrupted = 1;
    if (tsectl_signals < 100)
        tsectl_signals = tsectl_signals + 1;
}

#define TEXT_OF(x) #x
#define TEXT(x) TEXT_OF(x)

_Static_assert(FW_STEP_HZ == 200000u && FW_SEGMENT_HZ == 1000u, "info's help says the built-in rates");

static const char *const traj_help =
    "Streams a timed path with flow control.  FILE is CSV: rows t,x,y,z,roll,pitch,yaw (seconds,\n"
    "metres, radians), optionally a header row of those names first; '#' lines and blank lines are\n"
    "skipped.  Every row is checked before the bus is touched: a malformed row, a pose outside the\n"
    "wire's range (+-4 m, +-pi rad), or a time that does not increase by 1 ms to 60 s exits 2\n"
    "naming FILE:LINE.\n"
    "\n"
    "t is measured from the moment the controller starts the trajectory: it holds the plate at rest\n"
    "where it is now until it has traj_lead of the path (0.2 s by default; 'tsectl params get\n"
    "traj_lead'), or the last row, or a full queue, so no hold row is needed at the start.  Between\n"
    "rows the plate moves straight at constant speed (orientation slerped), so a row changes the speed\n"
    "at once: the first row must start gently from rest (it is usually the current pose, or a few\n"
    "millimetres from it), and later rows must ease in and out.  The controller measures slide\n"
    "acceleration over 10 ms, so a row may change a slide's speed by about slide_amax x 10 ms (1 cm/s\n"
    "with the defaults).  Sample a smooth path 10 to 50 ms apart.\n"
    "\n"
    "Before sending, tsectl reads the controller's parameters, rates ('tsectl info'), pose and slides\n"
    "and checks the whole file with the controller's own validator at those rates: a row that would\n"
    "be refused exits 3 naming FILE:LINE, which limit and by how much, and nothing is sent.  Rows\n"
    "then stream with up to " TEXT(PROTO_TRAJ_WINDOW) " in flight within the room the controller reports, keeping\n"
    "its queue ahead; the rows/s reached is printed.  If a row is still refused while streaming, or\n"
    "you press Ctrl-C, tsectl sends STOP, waits until the robot is at rest, and exits 3 (130 for\n"
    "Ctrl-C or SIGTERM) naming the row: never part of a path left running.  A second Ctrl-C while\n"
    "it waits for rest sends ESTOP.  If the controller ends the trajectory itself (a STOP tsectl did\n"
    "not send, a fault, an underrun: the host fell behind, and the refusal of the late row says by\n"
    "how many ms; an e-stop), tsectl names which and the row, waits until the robot is at rest and\n"
    "exits 3.";

static const char *const path_help =
    "Plans a path through the waypoints from where the plate is, against the controller's own\n"
    "parameters and rates (read first), as fast as its slides allow, and streams it as 'trajectory'\n"
    "does: checked whole by the controller's validator first, STOP on a refusal or Ctrl-C.\n"
    "WAYPOINTS.csv is rows x,y,z,roll,pitch,yaw (metres, radians; '#' lines and blank lines skipped);\n"
    "a header may name the columns in any order and add t (the time a waypoint is passed, seconds\n"
    "from the start; empty where free) and v (the plate's speed from there on at most, m/s).  A bad\n"
    "row exits 2 naming FILE:LINE.  The path goes from the plate's pose to the first waypoint (unless\n"
    "it is there), then through every waypoint on a smooth curve, or with --blend M along straight\n"
    "pieces whose corners it cuts by at most M metres; rows are --period apart (default 0.02 s).\n"
    "--jerk J holds each slide's jerk to J m/s^3 as well ('controller': the limit its own moves keep\n"
    "to; the controller bounds no trajectory's jerk, so there is none by default; tse-kin plan\n"
    "--help).  A waypoint outside the workspace, or a path leaving it between two, exits 3 naming it,\n"
    "and nothing is sent.  --dry-run prints the plan's duration and how near each limit it runs, then\n"
    "its rows (a file 'tsectl trajectory' takes), and sends nothing (tse-kin plan plans offline).\n"
    "--plot FILE.png draws the plan before sending: the plate's path from above, its height, and each\n"
    "slide's speed row by row against the limit (python3-matplotlib).";

static const char *const params_help =
    "list              the parameters with their defaults, SI units, ranges and meaning (no bus)\n"
    "get NAME          one value, in SI units\n"
    "set NAME VALUE    VALUE in SI (m, rad, m/s, m/s^2, ratios) unless the name carries its unit\n"
    "                  (watchdog_ms, step_pulse_ns, can_kbps); angles also as NAME_deg in degrees.\n"
    "                  Only while disabled or in fault.  A value out of range exits 2 naming its\n"
    "                  unit and range; a set the controller refuses is explained\n"
    "dump              every value as a 'key = value' file (what tse-sim --params and tse-kin read)\n"
    "dump FILE         no bus: the set parameter file FILE gives, as a controller takes it (FILE read\n"
    "                  as tse-sim and tse-kin --params read it; a file they refuse exits 2 saying why)\n"
    "save              store the set in the controller's non-volatile memory";

const tsectl_command tsectl_commands[] = {
    {"enable", "enable", "Energise the drives (from disabled).", check_none, run_enable, 1, 0},
    {"disable", "disable", "De-energise the drives (only at rest); the slides keep their zero.", check_none,
     run_disable, 1, 0},
    {"home", "home [--wait]",
     "Find the homing switches, then go to the home pose.  --wait follows it to rest (also when a homing\n"
     "is already running: it waits for that one).\n"
     "Ctrl-C (or SIGTERM) while it waits stops the robot (STOP), waits until it is at rest and exits 130;\n"
     "a second Ctrl-C meanwhile sends ESTOP.",
     check_flags, run_home, 1, 0},
    {"clear", "clear", "Leave fault or e-stop (the e-stop input must be closed); the drives stay off.", check_none,
     run_clear, 1, 0},
    {"stop", "stop [--wait]",
     "Controlled stop along the path; drops the trajectory queue.  --wait follows it to rest; Ctrl-C\n"
     "meanwhile sends STOP again, a second Ctrl-C sends ESTOP.",
     check_flags, run_stop, 1, 0},
    {"estop", "estop", "Emergency stop: stepping ends at once; latched until cleared.", check_none, run_estop, 0, 0},
    {"move", "move X Y Z ROLL PITCH YAW [--duration S | --speed V] [--wait]",
     "Move the plate straight to a pose (metres, radians; roll about X first, yaw about Z last) in S\n"
     "seconds (default 2) or at plate speed V m/s; the controller stretches it to its limits and\n"
     "validates the whole path first.  --wait follows it to rest with progress.\n"
     "Ctrl-C (or SIGTERM) while it waits stops the robot (STOP), waits until it is at rest and exits 130;\n"
     "a second Ctrl-C meanwhile sends ESTOP.",
     check_move, run_move, 1, 0},
    {"status", "status [--json]", "One STATUS: state, fault, homing, drives, queue, and the plate pose and slides.",
     check_json, run_status, 1, 0},
    {"info", "info [--json]",
     "What the controller is (INFO): its firmware's version and the rates it runs at, step interrupts and\n"
     "control segments per second.  tsectl reads these before it judges anything by them (a trajectory or\n"
     "a path checked before sending, a parameter set explained); a controller whose firmware is older\n"
     "than INFO answers INFO_GET 'unknown': 'info' then exits 3, the others judge at the built-in rates\n"
     "(200000 Hz step interrupts, 1000 Hz control segments), which every such firmware ran at, and say\n"
     "so.",
     check_json, run_info, 1, 0},
    {"watch", "watch [--count N]", "Live telemetry: state, plate pose, slides (N STATUS lines, or until Ctrl-C).",
     check_watch, run_watch, 1, 0},
    {"params", "params list | get NAME | set NAME VALUE | dump [FILE] | save", params_help, check_params, run_params, 1, 0},
    {"trajectory", "trajectory FILE", traj_help, check_trajectory, run_trajectory, 1, 0},
    {"path", "path WAYPOINTS.csv [--blend M] [--period S] [--jerk J|controller] [--dry-run] [--plot FILE.png]",
     path_help, check_path,
     run_path, 1, 0},
    {"scan", "scan",
     "Find the controllers on the bus: INFO_GET (pages 0 and 1) to every node id 1..15, then a table of\n"
     "every node that answered within --timeout (default 2000 ms): its id, firmware version, board and\n"
     "rates.  Needs no --node.  Exits 4 when no controller answered; warns when two answer on one id.",
     check_scan, run_scan, 0, 1},
    {"node", "node set N",
     "Change the controller's node id to N (1..15): PARAM_SET of the parameter node, then PARAM_SAVE.\n"
     "It takes effect when the controller restarts (power cycle or reset); until then it answers on its\n"
     "current id.  Refused (exit 3, nothing changed) when a controller already answers on N.",
     check_node, run_node, 1, 0},
    {"flash", "flash IMAGE [--bitrate BPS] [--no-start]",
     "Update the controller's firmware over the bus (docs/protocol.md, Updating the firmware).  IMAGE is\n"
     "an image with its header (tse-image stamp); one whose header, length or CRC is wrong exits 2 with\n"
     "nothing sent.  A node running its application is asked to restart into its bootloader (refused\n"
     "while its drives may be on: disable first).  An image for another board, or too long for the\n"
     "application area, exits 3 before anything is erased.  Then erase (timed apart), the blocks with\n"
     "progress, verify (the bootloader's CRC of what it wrote, and its report of the image), and start\n"
     "it (--no-start: the board stays in its bootloader).\n"
     "Prints the transfer's duration and rate against the bus's limit, --bitrate / 8 bytes a second\n"
     "(default 500000 bit/s): on the wall clock, and as the time its frames need on such a bus.",
     check_flash, run_flash, 0, 0},
    {"heartbeat", "heartbeat", "Send the host heartbeat every 100 ms until interrupted (the controller's watchdog\n"
                                "stops the robot after watchdog_ms of silence while the drives are on).",
     check_none, run_heartbeat, 1, 0},
};
const int tsectl_command_count = (int)(sizeof tsectl_commands / sizeof tsectl_commands[0]);

static const tsectl_command *current;

static void usage(FILE *f)
{
    fprintf(f, "usage: tsectl --iface IF --node N [--timeout MS] COMMAND [args]\n"
               "       tsectl COMMAND --help\n"
               "       tsectl --version\n\ncommands:\n");
    for (int i = 0; i < tsectl_command_count; ++i)
        fprintf(f, "  %s\n", tsectl_commands[i].synopsis);
    fprintf(f, "\n--iface IF    SocketCAN interface (vcan0, can0)\n"
               "--node N      controller node 1..15\n"
               "--timeout MS  how long to wait for an answer (default 2000)\n"
               "\nexit status: 0 acknowledged, 1 bus error, 2 usage or bad file (nothing sent), 3 refused,\n"
               "4 no answer in time, 130 interrupted (a motion it started is stopped first; a second\n"
               "interrupt sends ESTOP)\n");
}

int usage_error(const char *cmd, const char *what, const char *arg)
{
    const tsectl_command *c = current;
    if (!c && cmd)
        for (int i = 0; i < tsectl_command_count; ++i)
            if (!strcmp(tsectl_commands[i].name, cmd))
                c = &tsectl_commands[i];
    ctl_error("%s%s%s%s%s", c ? c->name : "", c ? ": " : "", what, arg ? ": " : "", arg ? arg : "");
    if (c)
        fprintf(stderr, "usage: tsectl --iface IF %s%s   (tsectl %s --help)\n", c->any_node ? "" : "--node N ",
                c->synopsis, c->name);
    else
        fprintf(stderr, "(try 'tsectl --help')\n");
    return EXIT_USAGE;
}

static int is_help(const char *s)
{
    return !strcmp(s, "--help") || !strcmp(s, "-h") || !strcmp(s, "help");
}

int main(int argc, char **argv)
{
    const char *iface = NULL;
    long node = -1;
    int i = 1;
    for (; i < argc; ++i) {
        char *end;
        if (is_help(argv[i]) && strcmp(argv[i], "help") != 0) {
            usage(stdout);
            return EXIT_OK;
        } else if (!strcmp(argv[i], "--version")) {
            printf("tsectl %s\n", TSE_VERSION);
            return EXIT_OK;
        } else if (!strcmp(argv[i], "--iface")) {
            if (i + 1 >= argc)
                return usage_error(NULL, "--iface needs an interface name", NULL);
            iface = argv[++i];
        } else if (!strcmp(argv[i], "--node")) {
            if (i + 1 >= argc)
                return usage_error(NULL, "--node needs 1..15", NULL);
            node = strtol(argv[++i], &end, 10);
            if (*end || !*argv[i] || node < 1 || node > 15)
                return usage_error(NULL, "--node takes 1..15", argv[i]);
        } else if (!strcmp(argv[i], "--timeout")) {
            if (i + 1 >= argc)
                return usage_error(NULL, "--timeout needs milliseconds", NULL);
            const long t = strtol(argv[++i], &end, 10);
            if (*end || !*argv[i] || t < 10 || t > 600000)
                return usage_error(NULL, "--timeout takes 10..600000 ms", argv[i]);
            tsectl_timeout_ms = (int)t;
        } else if (argv[i][0] == '-') {
            return usage_error(NULL, "unknown option", argv[i]);
        } else {
            break;
        }
    }
    if (i >= argc)
        return usage_error(NULL, "a command is needed", NULL);
    const char *name = argv[i];
    if (!strcmp(name, "help")) {
        /* tsectl help [COMMAND] */
        if (i + 1 >= argc) {
            usage(stdout);
            return EXIT_OK;
        }
        name = argv[++i];
        for (int k = 0; k < tsectl_command_count; ++k)
            if (!strcmp(tsectl_commands[k].name, name)) {
                printf("usage: tsectl --iface IF --node N %s\n\n%s\n", tsectl_commands[k].synopsis, tsectl_commands[k].help);
                return EXIT_OK;
            }
        return usage_error(NULL, "unknown command", name);
    }
    for (int k = 0; k < tsectl_command_count; ++k)
        if (!strcmp(tsectl_commands[k].name, name))
            current = &tsectl_commands[k];
    if (!current)
        return usage_error(NULL, "unknown command", name);
    char **args = argv + i + 1;
    const int nargs = argc - i - 1;
    /* Help needs no bus. */
    for (int k = 0; k < nargs; ++k)
        if (is_help(args[k]) && strcmp(args[k], "help") != 0) {
            printf("usage: tsectl --iface IF %s%s\n\n%s\n", current->any_node ? "" : "--node N ", current->synopsis,
                   current->help);
            return EXIT_OK;
        }
    int done = 0;
    const int bad = current->check(nargs, args, &done);
    if (bad != EXIT_OK || done)
        return bad;
    if (!iface || (node < 0 && !current->any_node))
        return usage_error(NULL, !iface ? "--iface IF is needed for this command" : "--node N is needed for this command",
                           NULL);

    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    tlink l;
    if (link_open(&l, iface, node < 0 ? PROTO_BROADCAST : (uint8_t)node) != 0) {
        ctl_error("cannot open CAN interface %s: %s", iface, strerror(errno));
        return EXIT_BUS;
    }
    l.heartbeat = current->heartbeat;
    const int rc = current->run(&l, nargs, args);
    link_close(&l);
    return rc;
}
