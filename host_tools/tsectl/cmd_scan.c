/* scan: the controllers on the bus; node set N: a controller's node id (the parameter `node`,
 * taken at its next start: docs/board.md, "Node id and ENABLE level"). */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "ctl_params.h"
#include "scan.h"

#define ALL_NODES ((uint16_t)(((1u << (PROTO_NODE_MASK + 1u)) - 1u) & ~1u)) /* 1..15 */

int check_scan(int argc, char **argv, int *done)
{
    (void)done;
    return argc > 0 ? usage_error("scan", "unexpected argument", argv[0]) : EXIT_OK;
}

static void print_entry(int node, const scan_entry *e)
{
    char version[32] = "?", rates[48] = "?";
    if (e->info) {
        snprintf(version, sizeof version, "%d.%d.%d", e->about.major, e->about.minor, e->about.patch);
        snprintf(rates, sizeof rates, "%u Hz steps, %u Hz segments", e->about.rates.step_hz,
                 e->about.rates.segment_hz);
    } else if (e->info_unknown) {
        snprintf(version, sizeof version, "older than INFO");
    }
    const char *board = e->board ? (e->name[0] ? e->name : "(unnamed)")
                        : e->board_refused || e->info_unknown ? "(older than BOARD)"
                                                              : "?";
    printf("%4d  %-16s  %-18s  %s\n", node, version, board, rates);
    if (e->infos > 1)
        ctl_error("warning: node %d answered INFO_GET %d times: two controllers share node id %d (give each its own: "
                  "tsectl --node %d node set N)",
                  node, e->infos, node, node);
}

int run_scan(tlink *l, int argc, char **argv)
{
    (void)argc;
    (void)argv;
    scan_entry found[16];
    const int rc = scan_nodes(l, ALL_NODES, tsectl_timeout_ms, found);
    if (rc != EXIT_OK)
        return rc;
    int n = 0;
    for (int k = 1; k <= (int)PROTO_NODE_MASK; ++k)
        if (found[k].heard) {
            if (n++ == 0)
                printf("node  firmware          board               rates\n");
            print_entry(k, &found[k]);
        }
    if (n == 0) {
        ctl_error("no controller answered (INFO_GET to nodes 1..%u, %d ms): check the bus, its bit rate (can_kbps) "
                  "and that the controllers are powered",
                  PROTO_NODE_MASK, tsectl_timeout_ms);
        return tsectl_interrupted ? EXIT_INTERRUPTED : EXIT_TIMEOUT;
    }
    printf("%d controller%s answered\n", n, n == 1 ? "" : "s");
    return tsectl_interrupted ? EXIT_INTERRUPTED : EXIT_OK;
}

/* N of `node set N`: a whole number within the parameter's range, or -1 (said). */
static long node_id(const char *text)
{
    const fw_param_def *d = &fw_param_table[FP_NODE];
    char *end = NULL;
    errno = 0;
    const long n = strtol(text, &end, 10);
    if (!*text || *end || errno != 0 || n < d->min || n > d->max) {
        char what[160];
        snprintf(what, sizeof what, "'%.40s' is not a node id: a whole number %ld..%ld (nothing sent)", text,
                 (long)d->min, (long)d->max);
        usage_error("node", what, NULL);
        return -1;
    }
    return n;
}

int check_node(int argc, char **argv, int *done)
{
    (void)done;
    if (argc < 1 || strcmp(argv[0], "set") != 0)
        return usage_error("node", "needs set N", argc ? argv[0] : NULL);
    if (argc != 2)
        return usage_error("node", "set takes one node id", argc > 2 ? argv[2] : NULL);
    return node_id(argv[1]) < 0 ? EXIT_USAGE : EXIT_OK;
}

int run_node(tlink *l, int argc, char **argv)
{
    (void)argc;
    const long to = node_id(argv[1]);
    if (to < 0)
        return EXIT_USAGE;
    /* An id another controller answers on would put two on one id after the restart. */
    if (to != l->node) {
        scan_entry found[16];
        const int rc = scan_nodes(l, (uint16_t)(1u << to), tsectl_timeout_ms, found);
        if (rc != EXIT_OK)
            return rc;
        if (found[to].heard) {
            ctl_error("node id %ld is taken: a controller already answers on it (tsectl scan); nothing changed", to);
            return EXIT_REJECTED;
        }
    }
    proto_message rej;
    int32_t now;
    int rc = ctl_param_set(l, FP_NODE, (int32_t)to, &now, &rej);
    if (rc == EXIT_REJECTED)
        ctl_print_reject(&rej);
    if (rc != EXIT_OK)
        return rc;
    rc = ctl_params_save(l);
    if (rc != EXIT_OK) {
        ctl_error("node %u holds node = %ld but did not save it: it keeps id %u after a restart", l->node, to,
                  l->node);
        return rc;
    }
    printf("node %u: node id %ld set and saved; it takes effect at the controller's restart: address it as --node %ld "
           "afterwards (until then it answers as node %u)\n",
           l->node, (long)now, (long)now, l->node);
    return EXIT_OK;
}
