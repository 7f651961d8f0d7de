/* What the printed documents need of the message table, checked before anything is printed.
 *
 * The codec only needs ranges; a reader of protocol.md or the DBC also needs a doc for every
 * message and field, a unit for every scaled field, names a DBC reader accepts, and text that
 * fits a DBC string and a markdown cell (printable ASCII without '"' or '|').  A table that breaks
 * any of this is reported, one line per problem naming the message and field, and nothing is
 * printed. */
#ifndef PROTOGEN_TABLE_LINT_H
#define PROTOGEN_TABLE_LINT_H

#include <stdio.h>

#include "fw/proto_table.h"

/* Checks the n definitions of table, writing one line per problem to err.  Returns the number of
 * problems (0 when the table can be printed). */
int table_lint(const proto_def *table, int n, FILE *err);

/* The same for a table of codes (proto_code): values 0, 1, 2, ... in order, each with an
 * identifier for a name and words that print as they are.  `what` names the table in messages. */
int codes_lint(const proto_code *codes, const char *what, FILE *err);

#endif
