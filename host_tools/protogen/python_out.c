/* python/tse/_protocol.py: the message table and the parameter table as Python data, for the
 * client tse.can, which packs and reads frames from it as the firmware's codec does.  See
 * outputs.h. */
#include <ctype.h>
#include <stdio.h>
#include <string.h>

#include "flags_text.h"
#include "decimal_text.h"
#include "field_type.h"
#include "fw/params.h"
#include "fw/proto.h"
#include "outputs.h"
#include "param_text.h"

/* A Python string literal: quotes, backslashes and control characters escaped. */
static void py_str(FILE *out, const char *s)
{
    fputc('"', out);
    for (const unsigned char *p = (const unsigned char *)s; *p; ++p) {
        if (*p == '"' || *p == '\\')
            fprintf(out, "\\%c", *p);
        else if (*p < 0x20 || *p == 0x7f)
            fprintf(out, "\\x%02x", *p);
        else
            fputc(*p, out);
    }
    fputc('"', out);
}

static int py_double(FILE *out, double x, const char *what)
{
    char t[64];
    if (dec_shortest(x, t, sizeof t) != 0) {
        fprintf(stderr, "protogen: %s: %g does not print as a Python float\n", what, x);
        return -1;
    }
    /* "1" would read as an int: keep every number of a float column a float. */
    fprintf(out, "%s%s", t, strpbrk(t, ".eEn") ? "" : ".0");
    return 0;
}

/* The key the Python side uses for an enumeration a field names (proto_enums). */
static const char *enum_key(const proto_enum_entry *t)
{
    for (const proto_enum_def *e = proto_enums; e->table; ++e)
        if (e->table == t)
            return e->key;
    return NULL;
}

static int messages(FILE *out)
{
    fprintf(out, "# name: (function code, direction, length, fields); a field is\n"
                 "# (name, type, first byte, min raw, max raw, unit, scale, enumeration or None, doc).\n"
                 "MESSAGES = {\n");
    for (int i = 0; i < PM_COUNT; ++i) {
        const proto_def *d = &proto_table[i];
        fprintf(out, "    \"%s\": (0x%02X, \"%s\", %u, (\n", d->name, d->function,
                d->dir == PROTO_TO_CONTROLLER ? "to_controller" : "to_host", d->dlc);
        for (int k = 0; k < d->nfields; ++k) {
            const proto_field *f = &d->fields[k];
            const char *ek = f->values ? enum_key(f->values) : NULL;
            if (f->values && !ek) {
                fprintf(stderr, "protogen: %s.%s names an enumeration protogen does not know\n", d->name, f->name);
                return -1;
            }
            char what[96];
            snprintf(what, sizeof what, "%s.%s's scale", d->name, f->name);
            fprintf(out, "        (\"%s\", \"%s\", %u, %ld, %ld, ", f->name, ft_name(f->type), f->offset, (long)f->min,
                    (long)f->max);
            py_str(out, f->unit);
            fprintf(out, ", ");
            if (py_double(out, f->scale, what) != 0)
                return -1;
            if (ek)
                fprintf(out, ", \"%s\",\n         ", ek);
            else
                fprintf(out, ", None,\n         ");
            char meaning[4096];
            if (field_meaning((proto_msg)i, k, meaning, sizeof meaning) != 0)
                return -1;
            py_str(out, meaning);
            fprintf(out, "),\n");
        }
        fprintf(out, "    ), ");
        py_str(out, d->doc);
        fprintf(out, "),\n");
    }
    fprintf(out, "}\n\n");
    return 0;
}

static void enumerations(FILE *out)
{
    fprintf(out, "# Named values of the enumerated fields.\nENUMS = {\n");
    for (const proto_enum_def *d = proto_enums; d->table; ++d) {
        fprintf(out, "    \"%s\": {", d->key);
        for (const proto_enum_entry *e = d->table; e->name; ++e)
            fprintf(out, "%s%d: \"%s\"", e == d->table ? "" : ", ", (int)e->value, e->name);
        fprintf(out, "},\n");
    }
    fprintf(out, "}\n\n");
}

/* The codes a field carries for one reason, with their words (proto_code_tables). */
static void codes(FILE *out)
{
    fprintf(out, "# Codes a field carries for one reason, value: (name, words): REJECT's field // 16 for timing\n"
                 "# (slide_limit), its where for param_set (param_rule).\nCODES = {\n");
    for (const proto_code_def *d = proto_code_tables; d->table; ++d) {
        fprintf(out, "    \"%s\": {\n", d->key);
        for (const proto_code *c = d->table; c->name; ++c) {
            fprintf(out, "        %d: (\"%s\", ", (int)c->value, c->name);
            py_str(out, c->words);
            fprintf(out, "),\n");
        }
        fprintf(out, "    },\n");
    }
    fprintf(out, "}\n\n");
}

/* The parameters: the table's integers, and each spelling people write (param_text.h) with the
 * raw units one unit of it is. */
static int parameters(FILE *out)
{
    fprintf(out, "# Parameter id: (name, wire unit, min raw, max raw, default raw, doc).\nPARAMS = (\n");
    for (int id = 0; id < FP_COUNT; ++id) {
        const fw_param_def *p = &fw_param_table[id];
        fprintf(out, "    (\"%s\", ", p->name);
        py_str(out, p->unit);
        fprintf(out, ", %ld, %ld, %ld, ", (long)p->min, (long)p->max, (long)p->def);
        py_str(out, p->doc);
        fprintf(out, "),\n");
    }
    fprintf(out, ")\n\n# Spelling: (parameter id, raw units per unit of this spelling, unit). A name without a\n"
                 "# unit suffix is SI; angles also take NAME_deg.\nPARAM_SPELLINGS = {\n");
    for (int id = 0; id < FP_COUNT; ++id) {
        char name[64];
        for (int deg = 0; deg < 2; ++deg) {
            snprintf(name, sizeof name, "%s%s", fw_param_table[id].name, deg ? "_deg" : "");
            param_key k;
            if (param_lookup(name, &k) != 0)
                continue;
            if (k.id != id) {
                fprintf(stderr, "protogen: parameter spelling %s names parameter %d, not %d\n", name, k.id, id);
                return -1;
            }
            fprintf(out, "    \"%s\": (%d, ", name, id);
            if (py_double(out, k.per_unit, name) != 0)
                return -1;
            fprintf(out, ", ");
            py_str(out, k.unit);
            fprintf(out, "),\n");
        }
    }
    fprintf(out, "}\n");
    return 0;
}

int gen_python(FILE *out)
{
    fprintf(out, "# Generated by host_tools/protogen from the message table (firmware/include/fw/proto_messages.def)\n"
                 "# and the parameter table (firmware/include/fw/params.def): do not edit.  Regenerate with\n"
                 "#   cmake --build <build dir> --target protocol_docs\n"
                 "# Identifiers: id = function << NODE_BITS | node; integers little-endian; node 0 addresses\n"
                 "# every controller (only ESTOP and STOP honour it).\n\n"
                 "NODE_BITS = %d\nNODE_MASK = 0x%02X\nBROADCAST = %u\n\n"
                 "# TRAJ_COMMIT's flags, and the trajectory rows a host keeps in flight while it streams\n"
                 "# (within the free slots ACK and STATUS report).\n",
            PROTO_NODE_BITS, PROTO_NODE_MASK, PROTO_BROADCAST);
    for (const proto_flag *b = proto_traj_flags; b->name; ++b) {
        fprintf(out, "TRAJ_");
        for (const char *c = b->name; *c; ++c)
            fputc(toupper((unsigned char)*c), out);
        fprintf(out, " = %lu\n", (unsigned long)b->mask);
    }
    fprintf(out,
            "TRAJ_WINDOW = %d\n\n"
            "# REJECT's field for a timing refusal: slide + REJECT_LIMIT_STRIDE * the slide limit's code.\n"
            "REJECT_LIMIT_STRIDE = %d\n\n"
            "# The wire's units (raw counts per SI unit) and ranges (raw).\n"
            "UM_PER_M = %d\nURAD_PER_RAD = %d\nNM_PER_M = %d\nUS_PER_S = %d\nMS_PER_S = %d\nPER_MILLE = %d\n"
            "POS_MAX_UM = %d\nANGLE_MAX_URAD = %d\nDT_MIN_US = %d\nDT_MAX_US = %d\nMOVE_VALUE_MAX = %d\n\n",
            PROTO_TRAJ_WINDOW, PROTO_REJECT_LIMIT_STRIDE, PROTO_UM_PER_M, PROTO_URAD_PER_RAD, PROTO_NM_PER_M,
            PROTO_US_PER_S, PROTO_MS_PER_S, PROTO_PER_MILLE, PROTO_POS_MAX_UM, PROTO_ANGLE_MAX_URAD,
            PROTO_DT_MIN_US, PROTO_DT_MAX_US, PROTO_MOVE_VALUE_MAX);
    fprintf(out, "# STATUS's flags: the bit of each.\nSTATUS_FLAGS = {\n");
    for (const proto_flag *b = proto_status_flags; b->name; ++b)
        fprintf(out, "    \"%s\": 0x%02lX,\n", b->name, (unsigned long)b->mask);
    fprintf(out, "}\n\n");
    enumerations(out);
    codes(out);
    if (messages(out) != 0)
        return -1;
    return parameters(out);
}
