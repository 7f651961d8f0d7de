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
#include "fw/limits.h"
#include "fw/params.h"
#include "param_text.h"
#include "param_text_internal.h"
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

/* The wire integer of a value's text, VALUE_BAD, or VALUE_UNSURE when it lies so close to a half,
 * or to an end of the range, that double and exact arithmetic may fall on either side.  The rules:
 * one finite number as text.h's text_number reads it (1e-400 is an underflow, not 0); within the
 * range as written (before rounding: param_text.h); then rounded to the nearest integer. */
static int ref_value(int id, long double per_unit, const char *text, size_t len, int32_t *raw)
{
    double x;
    if (!ref_finite_number(text, len, &x))
        return VALUE_BAD;
    const long double r = (long double)x * per_unit;
    if (!(fabsl(r) < 4e9L))
        return VALUE_BAD;
    const long double eps = 1e-15L * (1.0L + fabsl(r));
    const fw_param_def *d = &fw_param_table[id];
    if (fabsl(r - d->min) <= eps || fabsl(r - d->max) <= eps)
        return VALUE_UNSURE;
    if (r < d->min || r > d->max)
        return VALUE_BAD;
    const long double frac = fabsl(r - truncl(r));
    if (fabsl(frac - 0.5L) <= eps)
        return VALUE_UNSURE;
    const long double rounded = roundl(r); /* halves away from zero */
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
    /* The set as the controller judges it, at its rates (the STEP pulse, the DIR set-up). */
    const fw_param_fault f = fw_params_judge_config(out, FW_STEP_HZ, FW_SEGMENT_HZ);
    return f.rule == FW_RULE_NONE ? REF_ACCEPTED : f.id < 0 ? 0 : line[f.id];
}

/* An accepted file with another set saved into it (param_file_merged, as PARAM_SAVE writes it):
 * reads back to that set, and every line of the file that does not set a changed value is
 * there, byte for byte, in its place. */
static void check_merged(const char *data, size_t size, const fw_param_set *s)
{
    static const int changed[] = {FP_PLATE_VMAX, FP_WATCHDOG_MS, FP_SLIDE_AMAX};
    fw_param_set t = *s;
    t.v[FP_PLATE_VMAX] = t.v[FP_PLATE_VMAX] == 250000 ? 260000 : 250000;
    t.v[FP_WATCHDOG_MS] = t.v[FP_WATCHDOG_MS] == 0 ? 700 : 0;
    t.v[FP_SLIDE_AMAX] = fw_param_table[FP_SLIDE_AMAX].def; /* maybe a change, maybe none */
    char *text = malloc(size + 1);
    FUZZ_CHECK(text != NULL);
    memcpy(text, data, size);
    text[size] = '\0';
    char *merged = param_file_merged(text, &t);
    FUZZ_CHECK(merged != NULL);
    const char *path = mem_file(merged, strlen(merged));
    fw_param_set back;
    fw_params_default(&back);
    char err[512];
    const int rc = param_file_read(path, &back, FW_RATES_BUILT_IN, err, sizeof err);
    if (rc != 0)
        fprintf(stderr, "%s\n", err);
    FUZZ_CHECK(rc == 0 && !memcmp(&back, &t, sizeof back));
    /* Line by line: kept unless it names a changed parameter (its key, before '=' and '#'). */
    const char *a = text, *b = merged;
    while (*a) {
        const size_t la = strcspn(a, "\n"), lb = strcspn(b, "\n");
        int names_changed = 0;
        char key[128];
        /* The key as the reader sees it: after a BOM on the first line. */
        const size_t bom = a == text && la >= 3 && !memcmp(a, "\xEF\xBB\xBF", 3) ? 3 : 0;
        const char *eq = memchr(a + bom, '=', la - bom), *hash = memchr(a + bom, '#', la - bom);
        if (eq && (!hash || eq < hash)) {
            size_t kl = (size_t)(eq - a) - bom;
            const char *k = ref_trim(a + bom, &kl);
            long double per_unit;
            snprintf(key, sizeof key, "%.*s", (int)(kl < 127 ? kl : 127), k);
            const int id = ref_lookup(key, strlen(key), &per_unit);
            for (size_t c = 0; c < sizeof changed / sizeof changed[0]; ++c)
                names_changed |= id == changed[c];
        }
        /* The last line may have had no end: one (LF or CRLF) is added when something follows. */
        const int last = !a[la];
        if (!names_changed)
            FUZZ_CHECK((last ? lb >= la : la == lb) && !memcmp(a, b, la));
        if (last)
            break;
        FUZZ_CHECK(b[lb] == '\n');
        a += la + 1;
        b += lb + 1;
    }
    free(merged);
    free(text);
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
    const int rc = param_file_read(path, &r, FW_RATES_BUILT_IN, err, sizeof err);
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
    const int rc = param_file_read(path, &s, FW_RATES_BUILT_IN, err, sizeof err);
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
    /* Saving needs a file that reads from the defaults, as tse-sim's does. */
    fw_param_set d;
    fw_params_default(&d);
    if (!(opt & 1) || param_file_read(path, &d, FW_RATES_BUILT_IN, err, sizeof err) == 0)
        check_merged(data, size, &s);
}
