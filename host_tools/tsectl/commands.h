/* tsectl's commands.  Each has a check, run before the bus is opened (usage errors and bad files
 * exit 2 with nothing sent; a command that needs no bus sets *done), and a run on the open link. */
#ifndef TSECTL_COMMANDS_H
#define TSECTL_COMMANDS_H

#include "tsectl.h"

typedef struct {
    const char *name;
    const char *synopsis;
    const char *help;
    int (*check)(int argc, char **argv, int *done);
    int (*run)(tlink *l, int argc, char **argv);
    int heartbeat; /* send host heartbeats while it runs */
    int any_node;  /* runs without --node (a look over the whole bus) */
} tsectl_command;

extern const tsectl_command tsectl_commands[];
extern const int tsectl_command_count;

/* "usage error" on stderr with the command's synopsis; returns EXIT_USAGE. */
int usage_error(const char *cmd, const char *what, const char *arg);

int check_none(int argc, char **argv, int *done);
int check_flags(int argc, char **argv, int *done); /* optional --wait only */

int run_enable(tlink *l, int argc, char **argv);
int run_disable(tlink *l, int argc, char **argv);
int run_clear(tlink *l, int argc, char **argv);
int run_stop(tlink *l, int argc, char **argv);
int run_estop(tlink *l, int argc, char **argv);
int run_home(tlink *l, int argc, char **argv);
int run_heartbeat(tlink *l, int argc, char **argv);

int check_move(int argc, char **argv, int *done);
int run_move(tlink *l, int argc, char **argv);

int check_json(int argc, char **argv, int *done); /* optional --json only */
int run_status(tlink *l, int argc, char **argv);
int run_info(tlink *l, int argc, char **argv);
int check_watch(int argc, char **argv, int *done);
int run_watch(tlink *l, int argc, char **argv);

int check_params(int argc, char **argv, int *done);
int run_params(tlink *l, int argc, char **argv);

int check_trajectory(int argc, char **argv, int *done);
int run_trajectory(tlink *l, int argc, char **argv);

int check_path(int argc, char **argv, int *done);
int run_path(tlink *l, int argc, char **argv);

int check_scan(int argc, char **argv, int *done);
int run_scan(tlink *l, int argc, char **argv);
int check_node(int argc, char **argv, int *done);
int run_node(tlink *l, int argc, char **argv);

int check_flash(int argc, char **argv, int *done);
int run_flash(tlink *l, int argc, char **argv);

#endif
