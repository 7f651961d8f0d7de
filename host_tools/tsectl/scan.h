/* The controllers on a bus: INFO_GET pages 0 and 1 (docs/protocol.md) to node ids, and what each
 * answers, read from every node's frames at once. */
#ifndef TSECTL_SCAN_H
#define TSECTL_SCAN_H

#include <stdbool.h>
#include <stdint.h>

#include "ctl_info.h"
#include "tsectl.h"

typedef struct {
    ctl_info about;     /* version and rates, when info */
    int infos;          /* INFOs counted: more than one, two controllers on this id */
    bool heard;         /* any frame from the node (an answer, or its STATUS) */
    bool info;          /* INFO came */
    bool info_unknown;  /* INFO_GET refused unknown: a firmware older than INFO */
    bool board;         /* BOARD came: name below */
    bool board_refused; /* page 1 refused: a firmware older than BOARD */
    char name[9];       /* BOARD's characters, NUL-terminated */
} scan_entry;

/* Asks every node whose bit is set in `nodes` (bit k: node k, 1..15) and reads what comes for
 * wait_ms, or until every one asked has answered both pages.  out[k] for node k (out[0] unused).
 * The link is back on its own node afterwards.  Returns EXIT_OK, or EXIT_BUS (said). */
int scan_nodes(tlink *l, uint16_t nodes, int wait_ms, scan_entry out[16]);

#endif
