#include "csv.h"

#include <ctype.h>
#include <errno.h>
#include <stdlib.h>

int csv_parse_row(const char *line, double *out, int max, const char **why)
{
    int n = 0;
    const char *p = line;
    for (;;) {
        while (*p == ' ' || *p == '\t')
            ++p;
        if (*p == ',' || *p == '\0' || *p == '\n' || *p == '\r') {
            *why = "empty field";
            return -1;
        }
        if (n == max) {
            *why = "too many fields";
            return -1;
        }
        char *end;
        errno = 0;
        out[n] = strtod(p, &end);
        if (end == p) {
            *why = "not a number";
            return -1;
        }
        ++n;
        p = end;
        while (*p == ' ' || *p == '\t')
            ++p;
        if (*p == ',') {
            ++p;
            continue;
        }
        if (*p == '\r')
            ++p;
        if (*p == '\n')
            ++p;
        if (*p != '\0') {
            *why = "trailing text";
            return -1;
        }
        return n;
    }
}
