#include "tse/status.h"

#include <string.h>

static const char *const status_names[TSE_STATUS_COUNT] = {
    "ok", "invalid", "unreachable", "below", "alpha", "stroke", "singular", "degenerate", "noconverge",
};

const char *tse_status_name(tse_status s)
{
    if ((unsigned)s >= (unsigned)TSE_STATUS_COUNT)
        return "?";
    return status_names[s];
}

int tse_status_parse(const char *name, tse_status *out)
{
    if (name == NULL)
        return -1;
    for (int i = 0; i < TSE_STATUS_COUNT; ++i) {
        if (strcmp(name, status_names[i]) == 0) {
            *out = (tse_status)i;
            return 0;
        }
    }
    return -1;
}
