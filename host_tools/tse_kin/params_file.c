#include "params_file.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    const char *key;
    tse_param_id id;
    int degrees;
} key_def;

static const key_def keys[] = {
    {"L", TSE_PARAM_L, 0},           {"k1", TSE_PARAM_K1, 0},
    {"eta_deg", TSE_PARAM_ETA, 1},   {"k3", TSE_PARAM_K3, 0},
    {"k4", TSE_PARAM_K4, 0},         {"alpha_min_deg", TSE_PARAM_ALPHA_MIN, 1},
    {"alpha_max_deg", TSE_PARAM_ALPHA_MAX, 1}, {"s_min", TSE_PARAM_S_MIN, 0},
    {"s_max", TSE_PARAM_S_MAX, 0},   {"mu_min", TSE_PARAM_MU_MIN, 0},
    {"nu_min", TSE_PARAM_NU_MIN, 0},
};

const char *kin_param_key(tse_param_id id)
{
    for (size_t i = 0; i < sizeof keys / sizeof keys[0]; ++i)
        if (keys[i].id == id)
            return keys[i].key;
    return "?";
}

void kin_params_default(kin_param_values *p)
{
    memset(p, 0, sizeof *p);
    p->v[TSE_PARAM_L] = 1.727;
    p->v[TSE_PARAM_K1] = 0.2647;
    p->v[TSE_PARAM_ETA] = M_PI / 6.0;
    p->v[TSE_PARAM_K3] = 0.0186;
    p->v[TSE_PARAM_K4] = 0.11765;
    p->v[TSE_PARAM_ALPHA_MIN] = asin(0.324 / 1.727);
    p->v[TSE_PARAM_ALPHA_MAX] = asin(1.619 / 1.727);
    p->v[TSE_PARAM_S_MIN] = 0.0;
    p->v[TSE_PARAM_S_MAX] = 0.90;
    p->v[TSE_PARAM_MU_MIN] = 0.05;
    p->v[TSE_PARAM_NU_MIN] = 1e-3;
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

int kin_params_parse(const char *text, const char *name, kin_param_values *out, char *err, size_t errlen)
{
    kin_param_values p = *out;
    int seen[TSE_PARAM_COUNT] = {0};
    int lineno = 0;
    const char *cur = text;
    while (*cur) {
        ++lineno;
        const char *nl = strchr(cur, '\n');
        const size_t len = nl ? (size_t)(nl - cur) : strlen(cur);
        char buf[512];
        if (len >= sizeof buf) {
            snprintf(err, errlen, "%s:%d: line too long", name, lineno);
            return -1;
        }
        memcpy(buf, cur, len);
        buf[len] = '\0';
        cur = nl ? nl + 1 : cur + len;
        char *hash = strchr(buf, '#');
        if (hash)
            *hash = '\0';
        char *line = trim(buf);
        if (*line == '\0')
            continue;
        char *eq = strchr(line, '=');
        if (!eq) {
            snprintf(err, errlen, "%s:%d: expected 'key = value', got '%s'", name, lineno, line);
            return -1;
        }
        *eq = '\0';
        char *key = trim(line), *val = trim(eq + 1);
        const key_def *kd = NULL;
        for (size_t i = 0; i < sizeof keys / sizeof keys[0]; ++i)
            if (strcmp(keys[i].key, key) == 0)
                kd = &keys[i];
        if (!kd) {
            snprintf(err, errlen, "%s:%d: unknown key '%s'", name, lineno, key);
            return -1;
        }
        if (seen[kd->id]) {
            snprintf(err, errlen, "%s:%d: '%s' given twice (first on line %d)", name, lineno, key, seen[kd->id]);
            return -1;
        }
        errno = 0;
        char *end;
        const double x = strtod(val, &end);
        if (*val == '\0' || *end != '\0' || errno == ERANGE || !isfinite(x)) {
            snprintf(err, errlen, "%s:%d: '%s' is not a finite number for %s", name, lineno, val, key);
            return -1;
        }
        seen[kd->id] = lineno;
        p.v[kd->id] = kd->degrees ? x * M_PI / 180.0 : x;
        p.line[kd->id] = lineno;
    }
    tse_params tp;
    tp.L = p.v[TSE_PARAM_L];
    tp.k1 = p.v[TSE_PARAM_K1];
    tp.eta = p.v[TSE_PARAM_ETA];
    tp.k3 = p.v[TSE_PARAM_K3];
    tp.k4 = p.v[TSE_PARAM_K4];
    tp.alpha_min = p.v[TSE_PARAM_ALPHA_MIN];
    tp.alpha_max = p.v[TSE_PARAM_ALPHA_MAX];
    tp.s_min = p.v[TSE_PARAM_S_MIN];
    tp.s_max = p.v[TSE_PARAM_S_MAX];
    tp.mu_min = p.v[TSE_PARAM_MU_MIN];
    tp.nu_min = p.v[TSE_PARAM_NU_MIN];
    const tse_param_id bad = tse_params_check(&tp);
    if (bad != TSE_PARAM_OK) {
        if (p.line[bad])
            snprintf(err, errlen, "%s:%d: invalid value of %s (kinematics.md: see the valid parameter sets)",
                     name, p.line[bad], kin_param_key(bad));
        else
            snprintf(err, errlen, "%s: the default value of %s is invalid with the values given",
                     name, kin_param_key(bad));
        return -1;
    }
    *out = p;
    return 0;
}

int kin_params_load(const char *path, kin_param_values *p, char *err, size_t errlen)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        snprintf(err, errlen, "%s: cannot open: %s", path, strerror(errno));
        return -2;
    }
    char text[65536];
    const size_t n = fread(text, 1, sizeof text - 1, f);
    const int too_big = !feof(f);
    const int failed = ferror(f);
    fclose(f);
    if (failed) {
        snprintf(err, errlen, "%s: read error", path);
        return -2;
    }
    if (too_big) {
        snprintf(err, errlen, "%s: larger than 64 KiB", path);
        return -1;
    }
    text[n] = '\0';
    if (memchr(text, '\0', n)) {
        snprintf(err, errlen, "%s: not a text file", path);
        return -1;
    }
    return kin_params_parse(text, path, p, err, errlen);
}
