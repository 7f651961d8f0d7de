/* Parameter file parser: see params_file.h for the promise. */
#include "params_file.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define KIN_PI 3.14159265358979323846

typedef struct {
    tse_param_id id;
    const char *key;  /* tse_param_name(id), plus "_deg" for angles (checked by the unit tests) */
    int degrees;
    const char *rule; /* kinematics.md, "Valid parameter sets", in the file's units */
} key_def;

static const key_def keys[] = {
    {TSE_PARAM_L, "L", 0, "L > 0"},
    {TSE_PARAM_K1, "k1", 0, "0 < k1 <= 1"},
    {TSE_PARAM_ETA, "eta_deg", 1, "-90 < eta_deg < 90"},
    {TSE_PARAM_K3, "k3", 0, "k3 >= 0"},
    {TSE_PARAM_K4, "k4", 0, "k4 > 0"},
    {TSE_PARAM_ALPHA_MIN, "alpha_min_deg", 1, "0 < alpha_min_deg < 90"},
    {TSE_PARAM_ALPHA_MAX, "alpha_max_deg", 1, "alpha_min_deg < alpha_max_deg < 90"},
    {TSE_PARAM_S_MIN, "s_min", 0, "s_min >= 0"},
    {TSE_PARAM_S_MAX, "s_max", 0, "s_min < s_max"},
    {TSE_PARAM_MU_MIN, "mu_min", 0, "0 <= mu_min < 1"},
    {TSE_PARAM_NU_MIN, "nu_min", 0, "0 <= nu_min < 1"},
};
enum { N_KEYS = (int)(sizeof keys / sizeof keys[0]) };

static const key_def *key_of_id(tse_param_id id)
{
    for (int i = 0; i < N_KEYS; ++i)
        if (keys[i].id == id)
            return &keys[i];
    return NULL;
}

const char *kin_param_key(tse_param_id id)
{
    const key_def *k = key_of_id(id);
    return k ? k->key : "?";
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

void kin_params_describe_invalid(const kin_param_values *p, tse_param_id bad, const char *name,
                                 const char *context, char *err, size_t errlen)
{
    const key_def *k = key_of_id(bad);
    if (!k) {
        snprintf(err, errlen, "%s: invalid parameter set%s", name, context);
        return;
    }
    /* Shown in the file's units, with enough digits that a value just past a bound is visible. */
    const double shown = k->degrees ? p->v[bad] * (180.0 / KIN_PI) : p->v[bad];
    if (p->line[bad] > 0)
        snprintf(err, errlen, "%s:%d: %s = %.15g is invalid%s (needs %s)", name, p->line[bad], k->key, shown,
                 context, k->rule);
    else
        snprintf(err, errlen, "%s: default value %s = %.15g is invalid%s with the values given (needs %s)", name,
                 k->key, shown, context, k->rule);
}

static char *trim(char *s)
{
    while (isspace((unsigned char)*s))
        ++s;
    char *e = s + strlen(s);
    while (e > s && isspace((unsigned char)e[-1]))
        *--e = '\0';
    return s;
}

static const key_def *key_of_name(const char *name)
{
    for (int i = 0; i < N_KEYS; ++i)
        if (!strcmp(keys[i].key, name))
            return &keys[i];
    return NULL;
}

/* The whole token must be one finite number in range: "1.5x", "", "nan" and "1e999" are refused. */
static int parse_value(const char *s, double *out)
{
    if (*s == '\0')
        return -1;
    char *end;
    errno = 0;
    const double x = strtod(s, &end);
    if (end == s || *end != '\0' || errno == ERANGE || !isfinite(x))
        return -1;
    *out = x;
    return 0;
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

/* One line (comment and surrounding blanks included); 0, or -1 with the message in err. */
static int parse_line(char *buf, int lineno, const char *name, kin_param_values *p, char *err, size_t errlen)
{
    char *hash = strchr(buf, '#');
    if (hash)
        *hash = '\0';
    char *line = trim(buf);
    if (*line == '\0')
        return 0;
    char *eq = strchr(line, '=');
    if (!eq) {
        snprintf(err, errlen, "%s:%d: expected 'key = value', got '%s'", name, lineno, line);
        return -1;
    }
    *eq = '\0';
    const char *key = trim(line), *val = trim(eq + 1);
    const key_def *k = key_of_name(key);
    if (!k) {
        snprintf(err, errlen,
                 "%s:%d: unknown key '%s' (keys: L, k1, eta_deg, k3, k4, alpha_min_deg, alpha_max_deg, s_min, "
                 "s_max, mu_min, nu_min)",
                 name, lineno, key);
        return -1;
    }
    if (p->line[k->id] > 0) {
        snprintf(err, errlen, "%s:%d: '%s' given twice (first on line %d)", name, lineno, key, p->line[k->id]);
        return -1;
    }
    double x;
    if (parse_value(val, &x) != 0) {
        snprintf(err, errlen, "%s:%d: value of %s is not a finite number: '%s'", name, lineno, key, val);
        return -1;
    }
    p->v[k->id] = k->degrees ? x * (KIN_PI / 180.0) : x;
    p->line[k->id] = lineno;
    return 0;
}

kin_params_outcome kin_params_parse(const char *text, const char *name, kin_param_values *out, char *err,
                                    size_t errlen)
{
    kin_param_values p = *out;
    /* Lines already recorded belong to some earlier parse; duplicates are judged within this text. */
    memset(p.line, 0, sizeof p.line);
    int lineno = 0;
    for (const char *cur = text; *cur;) {
        ++lineno;
        const char *nl = strchr(cur, '\n');
        const size_t len = nl ? (size_t)(nl - cur) : strlen(cur);
        if (len >= KIN_PARAMS_MAX_LINE) {
            snprintf(err, errlen, "%s:%d: line longer than %d characters", name, lineno, KIN_PARAMS_MAX_LINE - 1);
            return KIN_PARAMS_BAD;
        }
        char buf[KIN_PARAMS_MAX_LINE];
        memcpy(buf, cur, len);
        buf[len] = '\0';
        cur = nl ? nl + 1 : cur + len;
        if (parse_line(buf, lineno, name, &p, err, errlen) != 0)
            return KIN_PARAMS_BAD;
    }
    tse_params t;
    to_tse(&p, &t);
    const tse_param_id bad = tse_params_check(&t);
    if (bad != TSE_PARAM_OK) {
        kin_params_describe_invalid(&p, bad, name, "", err, errlen);
        return KIN_PARAMS_BAD;
    }
    *out = p;
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
    fclose(f);
    return r;
}
