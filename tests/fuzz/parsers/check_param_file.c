/* The controller's SI parameter file (param_text.h) against its rules read independently: the set
 * an accepted file gives, the line a refused one is refused at, a refused file's set left as it
 * was, and every accepted value written as the writer writes it reading back to itself. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "checks.h"
#include "fuzz_target.h"
#include "fw/params.h"
#include "param_text.h"
#include "ref_text.h"

static const long double PI_L = 3.141592653589793238462643383279502884L;

/* param_text.h: a table name is SI (a micro-unit of the wire becomes one SI unit: 1e6 raw
 * units), an angle's name + "_deg" is in degrees.  Returns the id or -1, with raw units per unit. */
static int ref_lookup(const char *name, size_t len, long double *per_unit)
{
    for (int id = 0; id < FP_COUNT; ++id) {
        const char *t = fw_param_table[id].name, *unit = fw_param_table[id].unit;
        const size_t n = strlen(t);
        const int micro = unit[0] == 'u' || !strcmp(unit, "ppm");
        if (len == n && !strncasecmp(name, t, n)) {
            *per_unit = micro ? 1e6L : 1.0L;
            return id;
        }
        if (!strcmp(unit, "urad") && len == n + 4 && !strncasecmp(name, t, n) && !strncasecmp(name + n, "_deg", 4)) {
            *per_unit = 1e6L * PI_L / 180.0L;
            return id;
        }
    }
    return -1;
}

enum { VALUE_BAD = -1, VALUE_UNSURE = -2 };

/* The wire integer of a value's text, VALUE_BAD, or VALUE_UNSURE when it lies so close to a half
 * that double and exact arithmetic may round it apart. */
static int ref_value(int id, long double per_unit, const char *text, size_t len, int32_t *raw)
{
    double x;
    if (!ref_number(text, len, &x) || !isfinite(x))
        return VALUE_BAD;
    const long double r = (long double)x * per_unit;
    if (!(fabsl(r) < 4e9L))
        return VALUE_BAD;
    const long double frac = fabsl(r - truncl(r));
    if (fabsl(frac - 0.5L) <= 1e-15L * (1.0L + fabsl(r)))
        return VALUE_UNSURE;
    const long double rounded = roundl(r); /* halves away from zero */
    const fw_param_def *d = &fw_param_table[id];
    if (rounded < d->min || rounded > d->max)
        return VALUE_BAD;
    if (id == FP_CAN_KBPS && rounded != 125 && rounded != 250 && rounded != 500 && rounded != 1000)
        return VALUE_BAD;
    *raw = (int32_t)rounded;
    return 0;
}

enum { REF_ACCEPTED = -1, REF_UNSURE = -2 };

/* The file by the rules, over base: the line it is refused at (0: a refusal naming no line),
 * REF_ACCEPTED with the set in *out, or REF_UNSURE. */
static int ref_param_file(const char *data, size_t size, const fw_param_set *base, fw_param_set *out)
{
    if (memchr(data, '\0', size))
        return 0;
    *out = *base;
    int line[FP_COUNT] = {0};
    size_t i = size >= 3 && !memcmp(data, "\xEF\xBB\xBF", 3) ? 3 : 0;
    for (int lineno = 1; i < size; ++lineno) {
        const char *nl = memchr(data + i, '\n', size - i);
        size_t len = (nl ? (size_t)(nl - data) : size) - i;
        const char *s = data + i;
        i += len + 1;
        const char *hash = memchr(s, '#', len);
        if (hash)
            len = (size_t)(hash - s);
        s = ref_trim(s, &len);
        if (len == 0)
            continue;
        const char *eq = memchr(s, '=', len);
        if (!eq)
            return lineno;
        size_t nlen = (size_t)(eq - s), vlen = len - nlen - 1;
        const char *name = ref_trim(s, &nlen), *value = ref_trim(eq + 1, &vlen);
        long double per_unit;
        const int id = ref_lookup(name, nlen, &per_unit);
        if (id < 0 || line[id])
            return lineno;
        const int v = ref_value(id, per_unit, value, vlen, &out->v[id]);
        if (v == VALUE_UNSURE)
            return REF_UNSURE;
        if (v == VALUE_BAD)
            return lineno;
        line[id] = lineno;
    }
    const int bad = fw_params_check(out);
    return bad < 0 ? REF_ACCEPTED : line[bad];
}

/* Valid, and unlike the defaults in a kinematic, a motion and a switch value. */
static void other_base(fw_param_set *s)
{
    fw_params_default(s);
    s->v[FP_L] = 1800000;
    s->v[FP_SLIDE_VMAX] = 120000;
    s->v[FP_HOME_SW_3] = 210000;
    s->v[FP_WATCHDOG_MS] = 0;
}

/* Every value through the writer's text (param_to_text, in SI and in degrees) and back; the whole
 * set as a file of those lines reads back to itself. */
static void check_written(const fw_param_set *s, unsigned opt)
{
    char text[8192];
    size_t n = 0;
    for (int id = 0; id < FP_COUNT; ++id) {
        param_key k;
        char buf[64];
        int32_t back = 0;
        char err[256];
        param_si_key(id, &k);
        param_to_text(&k, s->v[id], buf, sizeof buf);
        FUZZ_CHECK(param_from_text(&k, buf, &back, err, sizeof err) == 0 && back == s->v[id]);
        const int deg = !strcmp(fw_param_table[id].unit, "urad");
        if (deg) {
            char name[64];
            snprintf(name, sizeof name, "%s_deg", fw_param_table[id].name);
            param_key kd;
            FUZZ_CHECK(param_lookup(name, &kd) == 0 && kd.id == id);
            char dbuf[64];
            param_to_text(&kd, s->v[id], dbuf, sizeof dbuf);
            FUZZ_CHECK(param_from_text(&kd, dbuf, &back, err, sizeof err) == 0 && back == s->v[id]);
            if (opt & 2) {
                n += (size_t)snprintf(text + n, sizeof text - n, "%s = %s\n", name, dbuf);
                continue;
            }
        }
        n += (size_t)snprintf(text + n, sizeof text - n, "%s = %s\n", fw_param_table[id].name, buf);
    }
    FUZZ_CHECK(n < sizeof text);
    const char *path = mem_file(text, n);
    fw_param_set r;
    fw_params_default(&r);
    char err[512] = "";
    const int rc = param_file_read(path, &r, err, sizeof err);
    if (rc != 0)
        fprintf(stderr, "%s\n", err);
    FUZZ_CHECK(rc == 0 && !memcmp(&r, s, sizeof r));
}

void check_param_file(const char *data, size_t size, unsigned opt)
{
    fw_param_set s, before, want;
    if (opt & 1)
        other_base(&s);
    else
        fw_params_default(&s);
    FUZZ_CHECK(fw_params_check(&s) < 0);
    before = s;
    const int ref = ref_param_file(data, size, &before, &want);

    const char *path = mem_file(data, size);
    char err[512];
    memset(err, 'Z', sizeof err);
    const int rc = param_file_read(path, &s, err, sizeof err);
    if (rc != 0) {
        FUZZ_CHECK(rc == -1);
        FUZZ_CHECK(!memcmp(&s, &before, sizeof s));
        const int line = message_line(err, sizeof err, path);
        FUZZ_CHECK(ref == REF_UNSURE || line == ref);
        return;
    }
    FUZZ_CHECK(ref == REF_UNSURE || ref == REF_ACCEPTED);
    FUZZ_CHECK(fw_params_check(&s) < 0);
    if (ref == REF_ACCEPTED)
        FUZZ_CHECK(!memcmp(&s, &want, sizeof s));
    check_written(&s, opt);
}
