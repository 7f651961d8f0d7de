#include "text.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

char *text_trim(char *s)
{
    while (isspace((unsigned char)*s))
        ++s;
    char *e = s + strlen(s);
    while (e > s && isspace((unsigned char)e[-1]))
        *--e = '\0';
    return s;
}

/* One finite number for strtod, followed by blanks only when `blanks` allows them. */
static int number(const char *s, int blanks, double *out)
{
    char *end;
    errno = 0;
    const double x = strtod(s, &end);
    if (end == s || errno == ERANGE || !isfinite(x))
        return -1;
    while (blanks && isspace((unsigned char)*end))
        ++end;
    if (*end != '\0')
        return -1;
    *out = x;
    return 0;
}

int text_number(const char *s, double *out)
{
    return number(s, 0, out);
}

int text_value(const char *s, double *out)
{
    return number(s, 1, out);
}

int text_line_error(char *err, size_t errlen, const char *path, int line, const char *fmt, ...)
{
    char what[256];
    va_list ap;
    va_start(ap, fmt);
    /* ap was started on the line above; clang-tidy 14's analyzer calls it uninitialised since
     * python/csrc compiles this file a second time.  NOLINTNEXTLINE(clang-analyzer-valist.Uninitialized) */
    vsnprintf(what, sizeof what, fmt, ap);
    va_end(ap);
    snprintf(err, errlen, "%s:%d: %s", path, line, what);
    return -1;
}
