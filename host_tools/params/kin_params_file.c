/* Parameter file parser: see params_file.h for the promise. */
#include "kin_params_file.h"

#include "text.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "fw/params.h"
#include "line_reader.h"

#define KIN_PI 3.14159265358979323846

static const kin_param_key_def keys[] = {
    {TSE_PARAM_L, "L", 0, "m", "L > 0", "total scissor length"},
    {TSE_PARAM_K1, "k1", 0, "", "0 < k1 <= 1", "l0 / L, the lowest link's share of the length"},
    {TSE_PARAM_ETA, "eta", 0, "rad", "-pi/2 < eta < pi/2", "slide angle from the local x axis"},
    {TSE_PARAM_ETA, "eta_deg", 1, "deg", "-90 < eta_deg < 90", "slide angle from the local x axis"},
    {TSE_PARAM_K3, "k3", 0, "", "k3 >= 0", "r_act / L, radial offset of each scissor's slide origin"},
    {TSE_PARAM_K4, "k4", 0, "", "k4 > 0", "r_top / L, top plate radius (centre to ball joint)"},
    {TSE_PARAM_ALPHA_MIN, "alpha_min", 0, "rad", "0 < alpha_min < pi/2", "scissor angle stop, low"},
    {TSE_PARAM_ALPHA_MIN, "alpha_min_deg", 1, "deg", "0 < alpha_min_deg < 90", "scissor angle stop, low"},
    {TSE_PARAM_ALPHA_MAX, "alpha_max", 0, "rad", "alpha_min < alpha_max < pi/2", "scissor angle stop, high"},
    {TSE_PARAM_ALPHA_MAX, "alpha_max_deg", 1, "deg", "alpha_min_deg < alpha_max_deg < 90",
     "scissor angle stop, high"},
    {TSE_PARAM_S_MIN, "s_min", 0, "m", "s_min >= 0", "slide stroke, low end"},
    {TSE_PARAM_S_MAX, "s_max", 0, "m", "s_min < s_max", "slide stroke, high end"},
    {TSE_PARAM_MU_MIN, "mu_min", 0, "", "0 <= mu_min < 1", "type-1 singularity margin"},
    {TSE_PARAM_NU_MIN, "nu_min", 0, "", "0 <= nu_min < 1", "type-2 singularity margin"},
};
enum { N_KEYS = (int)(sizeof keys / sizeof keys[0]) };

int kin_param_keys(const kin_param_key_def **out)
{
    *out = keys;
    return N_KEYS;
}

static const kin_param_key_def *key_of(tse_param_id id, int degrees)
{
    for (int i = 0; i < N_KEYS; ++i)
        if (keys[i].id == id && keys[i].degrees == degrees)
            return &keys[i];
    return NULL;
}

static const kin_param_key_def *key_of_name(const char *name)
{
    for (int i = 0; i < N_KEYS; ++i)
        if (!strcmp(keys[i].key, name))
            return &keys[i];
    return NULL;
}

const char *kin_param_key(tse_param_id id)
{
    const kin_param_key_def *k = key_of(id, 0);
    return k ? k->key : "?";
}

/* The controller's parameters that are not kinematic, by their index in fw_param_table; -1 for
 * any other name. */
static int controller_only(const char *name)
{
    for (int i = 0; i < FP_COUNT; ++i)
        if (!strcmp(fw_param_table[i].name, name))
            return key_of_name(name) ? -1 : i;
    return -1;
}

int kin_param_is_controller_only(const char *name)
{
    return controller_only(name) >= 0;
}

void kin_params_default(kin_param_values *p)
{
    tse_params d;
    tse_params_default(&d);
    memset(p, 0, sizeof *p);
    p->v[TSE_PARAM_L] = d.L;
    p->v[TSE_PARAM_K1] = d.k1;
    p->v[TSE_PARAM_ETA] = d.eta;
    p->v[TSE_PARAM_K3] = d.k3;
    p->v[TSE_PARAM_K4] = d.k4;
    p->v[TSE_PARAM_ALPHA_MIN] = d.alpha_min;
    p->v[TSE_PARAM_ALPHA_MAX] = d.alpha_max;
    p->v[TSE_PARAM_S_MIN] = d.s_min;
    p->v[TSE_PARAM_S_MAX] = d.s_max;
    p->v[TSE_PARAM_MU_MIN] = d.mu_min;
    p->v[TSE_PARAM_NU_MIN] = d.nu_min;
}

int kin_params_is_prototype(const kin_param_values *p)
{
    kin_param_values d;
    kin_params_default(&d);
    for (int id = 1; id < TSE_PARAM_COUNT; ++id)
        if (!(fabs(p->v[id] - d.v[id]) <= 1e-12 * fabs(d.v[id])))
            return 0;
    return 1;
}

void kin_params_describe_invalid(const kin_param_values *p, tse_param_id bad, const char *name,
                                 const char *context, char *err, size_t errlen)
{
    /* In the spelling the file used, with enough digits that a value just past a bound is visible. */
    const int set = p->line[bad] > 0;
    const kin_param_key_def *k = key_of(bad, set && p->degrees[bad]);
    if (!k) {
        snprintf(err, errlen, "%s: invalid parameter set%s", name, context);
        return;
    }
    const double shown = k->degrees ? p->v[bad] * (180.0 / KIN_PI) : p->v[bad];
    char deg[48] = "";
    if (!k->degrees && !strcmp(k->unit, "rad"))
        snprintf(deg, sizeof deg, " (%.9g deg)", p->v[bad] * (180.0 / KIN_PI));
    if (set)
        snprintf(err, errlen, "%s:%d: %s = %.15g is invalid%s (needs %s)", name, p->line[bad], k->key, shown,
                 context, k->rule);
    else
        snprintf(err, errlen, "%s: default value %s = %.15g%s is invalid%s with the values given (needs %s)",
                 name, k->key, shown, deg, context, k->rule);
}


static void to_tse(const kin_param_values *p, tse_params *t)
{
    t->L = p->v[TSE_PARAM_L];
    t->k1 = p->v[TSE_PARAM_K1];
    t->eta = p->v[TSE_PARAM_ETA];
    t->k3 = p->v[TSE_PARAM_K3];
    t->k4 = p->v[TSE_PARAM_K4];
    t->alpha_min = p->v[TSE_PARAM_ALPHA_MIN];
    t->alpha_max = p->v[TSE_PARAM_ALPHA_MAX];
    t->s_min = p->v[TSE_PARAM_S_MIN];
    t->s_max = p->v[TSE_PARAM_S_MAX];
    t->mu_min = p->v[TSE_PARAM_MU_MIN];
    t->nu_min = p->v[TSE_PARAM_NU_MIN];
}

/* What one parse has seen so far: the parameters, and the lines of the ignored controller keys. */
typedef struct {
    kin_param_values p;
    int controller_line[FP_COUNT];
    const char *name;
    char *err;
    size_t errlen;
} parse_state;

__attribute__((format(printf, 3, 4))) static int fail(const parse_state *st, int lineno, const char *fmt, ...)
{
    char what[384];
    va_list ap;
    va_start(ap, fmt);
    /* ap was started on the line above; clang-tidy 14's analyzer calls it uninitialised since
     * python/csrc compiles this file a second time.  NOLINTNEXTLINE(clang-analyzer-valist.Uninitialized) */
    vsnprintf(what, sizeof what, fmt, ap);
    va_end(ap);
    snprintf(st->err, st->errlen, "%s:%d: %s", st->name, lineno, what);
    return -1;
}

static int value_of(const parse_state *st, int lineno, const char *key, const char *val, double *x)
{
    if (text_number(val, x) != 0)
        return fail(st, lineno, "value of %s is not a finite number: '%s'", key, val);
    return 0;
}

/* One line (comment and surrounding blanks included); 0, or -1 with the message in err. */
static int parse_line(char *buf, int lineno, parse_state *st)
{
    char *hash = strchr(buf, '#');
    if (hash)
        *hash = '\0';
    char *line = text_trim(buf);
    if (*line == '\0')
        return 0;
    char *eq = strchr(line, '=');
    if (!eq)
        return fail(st, lineno, "expected 'key = value', got '%s'", line);
    *eq = '\0';
    const char *key = text_trim(line), *val = text_trim(eq + 1);
    double x;
    const int ctl = controller_only(key);
    if (ctl >= 0) {
        if (st->controller_line[ctl] > 0)
            return fail(st, lineno, "'%s' given twice (first on line %d)", key, st->controller_line[ctl]);
        if (value_of(st, lineno, key, val, &x) != 0)
            return -1;
        st->controller_line[ctl] = lineno; /* the controller's: checked, not used here */
        return 0;
    }
    const kin_param_key_def *k = key_of_name(key);
    if (!k)
        return fail(st, lineno,
                    "unknown key '%s' (keys: L, k1, eta, k3, k4, alpha_min, alpha_max, s_min, s_max, mu_min, "
                    "nu_min; angles also as eta_deg, alpha_min_deg, alpha_max_deg; and the controller's "
                    "parameters, which 'tse-kin params' lists)",
                    key);
    kin_param_values *p = &st->p;
    if (p->line[k->id] > 0) {
        const kin_param_key_def *first = key_of(k->id, p->degrees[k->id]);
        if (first == k)
            return fail(st, lineno, "'%s' given twice (first on line %d)", key, p->line[k->id]);
        return fail(st, lineno, "'%s' and '%s' (line %d) are the same parameter; give one of them", key,
                    first->key, p->line[k->id]);
    }
    if (value_of(st, lineno, key, val, &x) != 0)
        return -1;
    p->v[k->id] = k->degrees ? x * (KIN_PI / 180.0) : x;
    p->line[k->id] = lineno;
    p->degrees[k->id] = k->degrees;
    return 0;
}

kin_params_outcome kin_params_parse(const char *text, const char *name, kin_param_values *out, char *err,
                                    size_t errlen)
{
    parse_state st;
    memset(&st, 0, sizeof st);
    st.p = *out;
    st.name = name;
    st.err = err;
    st.errlen = errlen;
    /* Lines already recorded belong to some earlier parse; duplicates are judged within this text. */
    memset(st.p.line, 0, sizeof st.p.line);
    memset(st.p.degrees, 0, sizeof st.p.degrees);
    int lineno = 0;
    for (const char *cur = text + utf8_bom_length(text, strlen(text)); *cur;) {
        ++lineno;
        const char *nl = strchr(cur, '\n');
        const size_t len = nl ? (size_t)(nl - cur) : strlen(cur);
        if (len > KIN_PARAMS_MAX_LINE) {
            snprintf(err, errlen, "%s:%d: line longer than %d characters", name, lineno, KIN_PARAMS_MAX_LINE);
            return KIN_PARAMS_BAD;
        }
        char buf[KIN_PARAMS_MAX_LINE + 1];
        memcpy(buf, cur, len);
        buf[len] = '\0';
        cur = nl ? nl + 1 : cur + len;
        if (parse_line(buf, lineno, &st) != 0)
            return KIN_PARAMS_BAD;
    }
    tse_params t;
    to_tse(&st.p, &t);
    const tse_param_id bad = tse_params_check(&t);
    if (bad != TSE_PARAM_OK) {
        kin_params_describe_invalid(&st.p, bad, name, "", err, errlen);
        return KIN_PARAMS_BAD;
    }
    *out = st.p;
    return KIN_PARAMS_OK;
}

kin_params_outcome kin_params_parse_stream(FILE *f, const char *name, kin_param_values *p, char *err,
                                           size_t errlen)
{
    char *text = malloc(KIN_PARAMS_MAX_BYTES + 1);
    if (!text) {
        snprintf(err, errlen, "%s: out of memory", name);
        return KIN_PARAMS_UNREADABLE;
    }
    errno = 0;
    const size_t n = fread(text, 1, KIN_PARAMS_MAX_BYTES + 1, f);
    const int read_errno = errno;
    kin_params_outcome r;
    if (ferror(f)) {
        snprintf(err, errlen, "%s: cannot read: %s", name, strerror(read_errno));
        r = KIN_PARAMS_UNREADABLE;
    } else if (n > KIN_PARAMS_MAX_BYTES) {
        snprintf(err, errlen, "%s: larger than %d bytes", name, KIN_PARAMS_MAX_BYTES);
        r = KIN_PARAMS_BAD;
    } else if (memchr(text, '\0', n)) {
        /* A NUL would silently end the text early: this is not a parameter file. */
        snprintf(err, errlen, "%s: contains a NUL byte (not a text file)", name);
        r = KIN_PARAMS_BAD;
    } else {
        text[n] = '\0';
        r = kin_params_parse(text, name, p, err, errlen);
    }
    free(text);
    return r;
}

kin_params_outcome kin_params_load(const char *path, kin_param_values *p, char *err, size_t errlen)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        snprintf(err, errlen, "%s: cannot open: %s", path, strerror(errno));
        return KIN_PARAMS_UNREADABLE;
    }
    const kin_params_outcome r = kin_params_parse_stream(f, path, p, err, errlen);
    (void)fclose(f); /* read only: the read's errors are in r */
    return r;
}
