/* Prints the CAN message table as it is compiled, one tab-separated line per message and field,
 * for the tests that check docs/tse_node1.dbc and docs/protocol.md against the table without
 * going through protogen (the program under test):
 *   M <name> <function> <dlc> <doc>
 *   F <message> <field> <type u8..i32> <offset> <min> <max> <scale %.17g> <unit> <doc>
 *   B <message> <field> <mask> <name> <doc>    (each bit of a field of bits, after its F line)
 * A string holding a tab or a line break would break the format: that is reported, exit 1. */
#include <stdio.h>
#include <string.h>

#include "fw/proto_table.h"

static const char *type_text(proto_field_type t)
{
    switch (t) {
    case PF_U8: return "u8";
    case PF_I8: return "i8";
    case PF_U16: return "u16";
    case PF_I16: return "i16";
    case PF_U24: return "u24";
    case PF_I24: return "i24";
    case PF_U32: return "u32";
    case PF_I32: return "i32";
    }
    return "?";
}

static int clean(const char *what, const char *s)
{
    if (s && !strpbrk(s, "\t\r\n"))
        return 1;
    fprintf(stderr, "table_dump: %s is missing or holds a tab or line break\n", what);
    return 0;
}

int main(void)
{
    int ok = 1;
    for (int i = 0; i < PM_COUNT; ++i) {
        const proto_def *d = &proto_table[i];
        ok &= clean(d->name ? d->name : "a message name", d->name) & clean(d->name, d->doc);
        printf("M\t%s\t%u\t%u\t%s\n", d->name, d->function, d->dlc, d->doc ? d->doc : "");
        for (int k = 0; k < d->nfields && k < PROTO_MAX_FIELDS; ++k) {
            const proto_field *f = &d->fields[k];
            ok &= clean("a field name", f->name) & clean("a unit", f->unit) & clean("a field doc", f->doc);
            printf("F\t%s\t%s\t%s\t%u\t%ld\t%ld\t%.17g\t%s\t%s\n", d->name, f->name ? f->name : "", type_text(f->type),
                   f->offset, (long)f->min, (long)f->max, f->scale, f->unit ? f->unit : "", f->doc ? f->doc : "");
            for (const proto_flag *b = proto_field_flags((proto_msg)i, k); b && b->name; ++b) {
                ok &= clean("a flag name", b->name) & clean("a flag doc", b->doc);
                printf("B\t%s\t%s\t%lu\t%s\t%s\n", d->name, f->name ? f->name : "", (unsigned long)b->mask, b->name,
                       b->doc ? b->doc : "");
            }
        }
    }
    return ok ? 0 : 1;
}
