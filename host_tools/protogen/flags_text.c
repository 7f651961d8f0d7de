#include "flags_text.h"

#include <stdio.h>

int field_meaning(proto_msg m, int k, char *buf, size_t n)
{
    const proto_flag *flags = proto_field_flags(m, k);
    int w = snprintf(buf, n, "%s", proto_table[m].fields[k].doc);
    for (const proto_flag *b = flags; b && b->name && w >= 0 && (size_t)w < n; ++b) {
        int bit = 0;
        while (bit < 31 && !((b->mask >> bit) & 1u))
            ++bit;
        w += snprintf(buf + w, n - (size_t)w, "%s bit %d %s (%s)", b == flags ? ":" : ";", bit, b->name, b->doc);
    }
    if (w >= 0 && (size_t)w < n)
        return 0;
    fprintf(stderr, "protogen: %s.%s: its meaning does not print in %zu characters\n", proto_table[m].name,
            proto_table[m].fields[k].name, n - 1);
    return -1;
}
