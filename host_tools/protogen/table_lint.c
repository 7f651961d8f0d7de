/* The message table checked for what the documents need.  See table_lint.h. */
#include "table_lint.h"

#include <math.h>
#include <stdint.h>

#include "field_type.h"

static const char *const where_from = "firmware/include/fw/proto_messages.def";

/* A DBC identifier: a letter or '_', then letters, digits and '_'. */
static int is_ident(const char *s)
{
    if (!s || !((*s >= 'A' && *s <= 'Z') || (*s >= 'a' && *s <= 'z') || *s == '_'))
        return 0;
    for (; *s; ++s)
        if (!((*s >= 'A' && *s <= 'Z') || (*s >= 'a' && *s <= 'z') || (*s >= '0' && *s <= '9') || *s == '_'))
            return 0;
    return 1;
}

/* Text that prints inside a DBC "..." string and a markdown table cell unchanged. */
static int is_plain(const char *s)
{
    for (; *s; ++s)
        if (*s < 0x20 || *s > 0x7E || *s == '"' || *s == '|')
            return 0;
    return 1;
}

static void type_range(proto_field_type t, int64_t *lo, int64_t *hi)
{
    const int b = ft_bits(t);
    const int sig = ft_signed(t);
    *lo = sig ? -((int64_t)1 << (b - 1)) : 0;
    *hi = sig ? ((int64_t)1 << (b - 1)) - 1 : ((int64_t)1 << b) - 1;
}

#define PROBLEM(...)                                                                                                   \
    do {                                                                                                               \
        fprintf(err, "%s: ", where_from);                                                                              \
        fprintf(err, __VA_ARGS__);                                                                                     \
        fprintf(err, "\n");                                                                                            \
        ++problems;                                                                                                    \
    } while (0)

int table_lint(const proto_def *table, int n, FILE *err)
{
    int problems = 0;
    for (int i = 0; i < n; ++i) {
        const proto_def *d = &table[i];
        const char *m = d->name ? d->name : "(unnamed)";
        if (!is_ident(d->name))
            PROBLEM("message %d: name '%s' is not an identifier", i, m);
        if (!d->doc || !d->doc[0] || !is_plain(d->doc))
            PROBLEM("%s: doc is missing or holds a control character, '\"', '|' or non-ASCII", m);
        if (d->nfields > PROTO_MAX_FIELDS) {
            PROBLEM("%s: %u fields, at most %d", m, d->nfields, PROTO_MAX_FIELDS);
            continue;
        }
        int next_free = 0; /* first byte after the previous field */
        for (int k = 0; k < d->nfields; ++k) {
            const proto_field *f = &d->fields[k];
            const char *fn = f->name ? f->name : "(unnamed)";
            if ((unsigned)f->type > PF_I32) {
                PROBLEM("%s.%s: unknown field type %d", m, fn, (int)f->type);
                continue;
            }
            int64_t lo, hi;
            type_range(f->type, &lo, &hi);
            /* REJECT's field index counts in byte order, so the table keeps that order. */
            if (f->offset < next_free)
                PROBLEM("%s.%s: starts at byte %u, inside or before the previous field (which ends before %d)", m, fn,
                        f->offset, next_free);
            next_free = f->offset + ft_bits(f->type) / 8;
            if (f->offset + ft_bits(f->type) / 8 > d->dlc)
                PROBLEM("%s.%s: bytes %u..%d lie past the message's %u", m, fn, f->offset,
                        f->offset + ft_bits(f->type) / 8 - 1, d->dlc);
            if (!is_ident(f->name))
                PROBLEM("%s field %d: name '%s' is not an identifier", m, k, fn);
            if (!f->doc || !f->doc[0] || !is_plain(f->doc))
                PROBLEM("%s.%s: doc is missing or holds a control character, '\"', '|' or non-ASCII", m, fn);
            if (!f->unit || !is_plain(f->unit))
                PROBLEM("%s.%s: unit is missing (use \"\") or holds a control character, '\"', '|' or non-ASCII", m,
                        fn);
            else if (f->scale != 1.0 && !f->unit[0])
                PROBLEM("%s.%s: scaled by %g but has no unit", m, fn, f->scale);
            if (!isfinite(f->scale) || f->scale <= 0.0)
                PROBLEM("%s.%s: scale %g is not a positive number", m, fn, f->scale);
            if (f->min > f->max || f->min < lo || f->max > hi)
                PROBLEM("%s.%s: range %ld..%ld is empty or outside its type's %lld..%lld", m, fn, (long)f->min,
                        (long)f->max, (long long)lo, (long long)hi);
            if (f->values)
                for (const proto_enum_entry *e = f->values; e->name; ++e)
                    if (!is_ident(e->name))
                        PROBLEM("%s.%s: value %d's name '%s' is not an identifier", m, fn, (int)e->value, e->name);
            /* The bits of a field of the firmware's own table (a planted table in a test has none). */
            const proto_flag *bits = table == proto_table ? proto_field_flags((proto_msg)i, k) : 0;
            uint32_t seen = 0;
            for (const proto_flag *b = bits; b && b->name; ++b) {
                if (!is_ident(b->name))
                    PROBLEM("%s.%s: flag '%s' is not an identifier", m, fn, b->name);
                if (!b->doc || !b->doc[0] || !is_plain(b->doc))
                    PROBLEM("%s.%s: flag %s's doc is missing or holds a control character, '\"', '|' or non-ASCII", m,
                            fn, b->name);
                if (b->mask == 0 || (b->mask & (b->mask - 1)) != 0 || b->mask > (uint32_t)f->max || (seen & b->mask))
                    PROBLEM("%s.%s: flag %s's mask 0x%lx is not one bit of its own inside the field", m, fn, b->name,
                            (unsigned long)b->mask);
                seen |= b->mask;
            }
        }
    }
    return problems;
}

int codes_lint(const proto_code *codes, const char *what, FILE *err)
{
    int problems = 0, i = 0;
    for (const proto_code *c = codes; c->name; ++c, ++i) {
        if (c->value != i)
            PROBLEM("%s: code '%s' has value %d where %d is due (codes count 0, 1, 2, ... in order)", what, c->name,
                    (int)c->value, i);
        if (!is_ident(c->name))
            PROBLEM("%s: code %d's name '%s' is not an identifier", what, (int)c->value, c->name);
        if (!c->words || !c->words[0] || !is_plain(c->words))
            PROBLEM("%s: code '%s': words are missing or hold a control character, '\"', '|' or non-ASCII", what,
                    c->name);
    }
    return problems;
}
