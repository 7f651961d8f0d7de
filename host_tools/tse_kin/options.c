/* Option parsing: see options.h for the promise. */
#include "options.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "csv.h"
#include "plan_text.h"
#include "text.h"

void kin_options_default(kin_options *o)
{
    memset(o, 0, sizeof *o);
    o->grid[0] = KIN_DEFAULT_GRID_R;
    o->grid[1] = KIN_DEFAULT_GRID_PHI;
    o->grid[2] = KIN_DEFAULT_GRID_Z;
    o->bench_n = KIN_DEFAULT_BENCH_N;
}

typedef struct {
    const char *name;
    unsigned bit;
    int takes_value; /* 0: a switch */
} option_def;

static const option_def defs[] = {
    {"--params", KIN_OPT_PARAMS, 1},
    {"--design", KIN_OPT_PARAMS, 1}, /* the same file, judged as a design: one of the two counts */
    {"--precision", KIN_OPT_PRECISION, 1},
    {"--grid", KIN_OPT_GRID, 1},
    {"--orientation", KIN_OPT_ORIENTATION, 1},
    {"--z", KIN_OPT_Z, 1},
    {"--n", KIN_OPT_N, 1},
    {"--points", KIN_OPT_POINTS, 0},
    {"--jobs", KIN_OPT_JOBS, 1},
    {"--blend", KIN_OPT_BLEND, 1},
    {"--period", KIN_OPT_PERIOD, 1},
    {"--jerk", KIN_OPT_JERK, 1},
};

/* A whole decimal number in [lo, hi], nothing around it. */
static int parse_long(const char *s, long lo, long hi, long *out)
{
    if (*s == '\0' || isspace((unsigned char)*s) || *s == '+')
        return -1;
    char *end;
    errno = 0;
    const long v = strtol(s, &end, 10);
    if (*end != '\0' || errno == ERANGE || v < lo || v > hi)
        return -1;
    *out = v;
    return 0;
}

static int all_finite(const double *v, int n)
{
    for (int k = 0; k < n; ++k)
        if (!isfinite(v[k]))
            return 0;
    return 1;
}

static int parse_grid(const char *s, int grid[3])
{
    /* Split by hand rather than through csv: counts are integers, "21.0" or "2e1" is a mistake. */
    char buf[64];
    const size_t len = strlen(s);
    if (len >= sizeof buf)
        return -1;
    memcpy(buf, s, len + 1);
    const long lo[3] = {2, 1, 2};
    long v[3];
    char *field = buf;
    for (int k = 0; k < 3; ++k) {
        char *comma = strchr(field, ',');
        if ((k < 2) != (comma != NULL))
            return -1;
        if (comma)
            *comma = '\0';
        if (parse_long(field, lo[k], KIN_GRID_MAX_AXIS, &v[k]) != 0)
            return -1;
        field = comma ? comma + 1 : field;
    }
    if (v[0] * v[1] * v[2] > KIN_GRID_MAX_POINTS)
        return -1;
    for (int k = 0; k < 3; ++k)
        grid[k] = (int)v[k];
    return 0;
}

static int apply(unsigned bit, const char *name, const char *val, kin_options *o, char *err, size_t errlen)
{
    const char *why;
    switch (bit) {
    case KIN_OPT_PARAMS:
        if (*val == '\0')
            break;
        o->params_path = val;
        o->params_design = !strcmp(name, "--design");
        return 0;
    case KIN_OPT_PRECISION:
        if (strcmp(val, "float") != 0 && strcmp(val, "double") != 0)
            break;
        o->use_float = !strcmp(val, "float");
        return 0;
    case KIN_OPT_GRID:
        o->grid_set = 1;
        if (parse_grid(val, o->grid) != 0) {
            snprintf(err, errlen,
                     "%s takes NR,NPHI,NZ: whole numbers with NR >= 2, NPHI >= 1, NZ >= 2, each at most %ld and "
                     "at most %ld points in all; got '%s'",
                     name, KIN_GRID_MAX_AXIS, KIN_GRID_MAX_POINTS, val);
            return -1;
        }
        return 0;
    case KIN_OPT_ORIENTATION:
        if (csv_parse_list(val, o->orientation, 3, &why) != 3 || !all_finite(o->orientation, 3)) {
            snprintf(err, errlen, "%s takes three finite angles R,P,Y in radians; got '%s'", name, val);
            return -1;
        }
        return 0;
    case KIN_OPT_Z: {
        const int n = csv_parse_list(val, o->z, KIN_MAX_Z, &why);
        if (n < 1 || !all_finite(o->z, n)) {
            snprintf(err, errlen, "%s takes 1 to %d finite heights Z1,Z2,... in metres; got '%s'", name,
                     KIN_MAX_Z, val);
            return -1;
        }
        o->n_z = n;
        return 0;
    }
    case KIN_OPT_N:
        o->n_set = 1;
        if (parse_long(val, 2, KIN_BENCH_MAX_N, &o->bench_n) != 0) {
            snprintf(err, errlen, "%s takes a whole number from 2 to %ld; got '%s'", name, KIN_BENCH_MAX_N, val);
            return -1;
        }
        return 0;
    case KIN_OPT_JOBS: {
        long j;
        if (parse_long(val, 1, KIN_MAX_JOBS, &j) != 0) {
            snprintf(err, errlen, "%s takes a whole number of threads from 1 to %d; got '%s'", name, KIN_MAX_JOBS,
                     val);
            return -1;
        }
        o->jobs = (int)j;
        return 0;
    }
    case KIN_OPT_BLEND:
        if (text_number(val, &o->blend) != 0 || !(o->blend >= 0.0 && o->blend <= KIN_BLEND_MAX)) {
            snprintf(err, errlen, "%s takes a corner tolerance in metres from 0 to %g; got '%s'", name, KIN_BLEND_MAX,
                     val);
            return -1;
        }
        return 0;
    case KIN_OPT_PERIOD:
        if (text_number(val, &o->period) != 0 || !(o->period >= KIN_PERIOD_MIN && o->period <= KIN_PERIOD_MAX)) {
            snprintf(err, errlen, "%s takes the rows' spacing in seconds from %g to %g; got '%s'", name, KIN_PERIOD_MIN,
                     KIN_PERIOD_MAX, val);
            return -1;
        }
        return 0;
    case KIN_OPT_JERK:
        if (plan_jerk_from_text(val, &o->jerk) != 0) {
            snprintf(err, errlen,
                     "%s takes the slides' jerk limit in m/s^3 above 0 and up to %g, or 'controller' for the "
                     "controller's own; got '%s'",
                     name, PLAN_JERK_MAX, val);
            return -1;
        }
        return 0;
    default:
        break;
    }
    snprintf(err, errlen, "%s: bad value '%s'%s", name, val,
             bit == KIN_OPT_PRECISION ? " (float or double)" : bit == KIN_OPT_PARAMS ? " (a file name)" : "");
    return -1;
}

int kin_options_parse(int n, char *const *args, unsigned allowed, kin_options *o, char *err, size_t errlen)
{
    for (int i = 0; i < n; ++i) {
        const char *a = args[i];
        if ((allowed & KIN_OPT_ARGS) && strncmp(a, "--", 2) != 0) {
            if (o->n_args == KIN_MAX_ARGS) {
                snprintf(err, errlen, "unexpected argument '%s' (at most %d are taken)", a, KIN_MAX_ARGS);
                return -1;
            }
            o->args[o->n_args++] = a;
            continue;
        }
        const char *eq = strncmp(a, "--", 2) ? NULL : strchr(a, '=');
        const size_t name_len = eq ? (size_t)(eq - a) : strlen(a);
        const option_def *d = NULL;
        for (size_t k = 0; k < sizeof defs / sizeof defs[0]; ++k)
            if (strlen(defs[k].name) == name_len && !strncmp(defs[k].name, a, name_len))
                d = &defs[k];
        if (!d) {
            snprintf(err, errlen, "unexpected argument '%s'", a);
            return -1;
        }
        if (!(allowed & d->bit)) {
            snprintf(err, errlen, "this command does not take %s", d->name);
            return -1;
        }
        if (!d->takes_value) {
            if (eq) {
                snprintf(err, errlen, "%s takes no value; got '%s'", d->name, a);
                return -1;
            }
            o->points = 1; /* --points is the only switch */
            continue;
        }
        const char *val;
        if (eq) {
            val = eq + 1;
        } else if (i + 1 < n) {
            val = args[++i];
        } else {
            snprintf(err, errlen, "%s needs a value", d->name);
            return -1;
        }
        if (apply(d->bit, d->name, val, o, err, errlen) != 0)
            return -1;
    }
    return 0;
}
