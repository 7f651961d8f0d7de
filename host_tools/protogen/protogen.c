/* Prints what the CAN message table says, in the forms people and tools read:
 *   protogen markdown        docs/protocol.md
 *   protogen dbc [NODE]      a DBC database for one controller (default node 1)
 *   protogen frames [NODE]   sample frames from the codec with their field values (for the test
 *                            that decodes them with a third-party DBC reader)
 *   protogen python          python/tse/_protocol.py (the tables for the client tse.can)
 * The table (fw/proto_table.h, made from firmware/include/fw/proto_messages.def) is the single
 * truth; the tests regenerate these outputs and fail when the committed documents differ.  A table
 * the documents cannot describe (see table_lint.h) is reported and nothing is printed. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fw/proto.h"
#include "outputs.h"
#include "table_lint.h"

/* Deterministic samples: each message with its fields at their bounds and in between. */
static int frames(FILE *out, unsigned node)
{
    unsigned seed = 12345u;
    for (int rep = 0; rep < 20; ++rep) {
        for (int i = 0; i < PM_COUNT; ++i) {
            const proto_def *d = &proto_table[i];
            proto_message m = {(proto_msg)i, (uint8_t)node, {0}};
            for (int k = 0; k < d->nfields; ++k) {
                seed = seed * 1103515245u + 12345u;
                const int64_t lo = d->fields[k].min, hi = d->fields[k].max;
                const uint64_t span = (uint64_t)(hi - lo) + 1u;
                m.v[k] = rep == 0   ? (int32_t)lo
                         : rep == 1 ? (int32_t)hi
                                    : (int32_t)(lo + (int64_t)((seed >> 1) % span));
            }
            hal_can_frame f;
            if (proto_encode(&m, &f) != 0) {
                fprintf(stderr, "protogen: the codec refused a %s frame inside the table's ranges\n", d->name);
                return -1;
            }
            fprintf(out, "%u,", f.id);
            for (int b = 0; b < f.len; ++b)
                fprintf(out, "%02X", f.data[b]);
            fprintf(out, ",%s", d->name);
            for (int k = 0; k < d->nfields; ++k)
                fprintf(out, ",%s=%ld", d->fields[k].name, (long)m.v[k]);
            fprintf(out, "\n");
        }
    }
    return 0;
}

/* Copies the finished document to stdout: a failure part-way leaves nothing printed. */
static int emit(FILE *doc)
{
    char buf[4096];
    size_t n;
    rewind(doc);
    while ((n = fread(buf, 1, sizeof buf, doc)) > 0)
        if (fwrite(buf, 1, n, stdout) != n)
            break;
    const int bad = ferror(doc) || ferror(stdout) || fflush(stdout) != 0;
    if (bad)
        fprintf(stderr, "protogen: could not write the output\n");
    return bad ? -1 : 0;
}

static int markdown(FILE *out, unsigned node)
{
    (void)node;
    return gen_markdown(out);
}

static int python(FILE *out, unsigned node)
{
    (void)node;
    return gen_python(out);
}

int main(int argc, char **argv)
{
    static const struct {
        const char *name;
        int (*gen)(FILE *, unsigned);
        int takes_node;
    } outputs[] = {{"markdown", markdown, 0}, {"dbc", gen_dbc, 1}, {"frames", frames, 1}, {"python", python, 0}};
    const char *const usage = "usage: protogen markdown | dbc [NODE] | frames [NODE] | python   (NODE 1..15)\n";
    int which = -1;
    for (int i = 0; argc >= 2 && i < (int)(sizeof outputs / sizeof outputs[0]); ++i)
        if (!strcmp(argv[1], outputs[i].name))
            which = i;
    if (which < 0 || argc > 2 + outputs[which].takes_node) {
        if (argc >= 2 && which < 0)
            fprintf(stderr, "protogen: unknown output '%s'\n", argv[1]);
        else if (argc >= 2)
            fprintf(stderr, "protogen: too many arguments for '%s'\n", argv[1]);
        fprintf(stderr, "%s", usage);
        return 2;
    }
    unsigned long node = 1;
    if (argc == 3) {
        char *end;
        node = strtoul(argv[2], &end, 10);
        if (end == argv[2] || *end || node < 1 || node > 15) {
            fprintf(stderr, "protogen: node '%s' is not 1..15\n%s", argv[2], usage);
            return 2;
        }
    }
    int problems = table_lint(proto_table, PM_COUNT, stderr);
    for (const proto_code_def *d = proto_code_tables; d->table; ++d)
        problems += codes_lint(d->table, d->key, stderr);
    if (problems != 0) {
        fprintf(stderr, "protogen: the message table cannot be printed as it is; nothing written\n");
        return 1;
    }
    FILE *doc = tmpfile();
    if (!doc) {
        fprintf(stderr, "protogen: no temporary file for the output\n");
        return 1;
    }
    const int ok = outputs[which].gen(doc, (unsigned)node) == 0 && emit(doc) == 0;
    (void)fclose(doc); /* a temporary file, already copied out (emit checked that) */
    return ok ? 0 : 1;
}
