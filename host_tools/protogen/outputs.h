/* The documents protogen prints from the message table (fw/proto_table.h).
 * Each writes the whole document to out and returns 0, or reports what could not be printed on
 * stderr and returns -1 (the caller then discards out, so no half document is left). The table is
 * assumed to have passed table_lint. */
#ifndef PROTOGEN_OUTPUTS_H
#define PROTOGEN_OUTPUTS_H

#include <stdio.h>

/* docs/protocol.md */
int gen_markdown(FILE *out);

/* A DBC database for one controller, node 1..15 (docs/tse_node1.dbc is node 1). */
int gen_dbc(FILE *out, unsigned node);

/* python/tse/_protocol.py: the message, enumeration and parameter tables as Python data. */
int gen_python(FILE *out);

#endif
