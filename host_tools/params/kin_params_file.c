/* The kinematic parameters of a parameter file: see kin_params_file.h for the promise. */
#define _POSIX_C_SOURCE 200809L /* strdup */
#include "kin_params_file.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fw/params.h"
#include "param_text.h"

#define KIN_PI PARAM_PI

#define DEG PARAM_DEG_SUFFIX

static const kin_param_key_def keys[] = {
    {TSE_PARAM_L, TSE_PARAM_NAME_L, 0, "m", "L > 0", "total scissor length"},
    {TSE_PARAM_K1, TSE_PARAM_NAME_K1, 0, "", "0 < k1 <= 1", "l0 / L, the lowest link's share of the length"},
    {TSE_PARAM_ETA, TSE_PARAM_NAME_ETA, 0, "rad", "-pi/2 < eta < pi/2", "slide angle from the local x axis"},
    {TSE_PARAM_ETA, TSE_PARAM_NAME_ETA DEG, 1, "deg", "-90 < eta_deg < 90", "slide angle from the local x axis"},
    {TSE_PARAM_K3, TSE_PARAM_NAME_K3, 0, "", "k3 >= 0", "r_act / L, radial offset of each scissor's slide origin"},
    {TSE_PARAM_K4, TSE_PARAM_NAME_K4, 0, "", "k4 > 0", "r_top / L, top plate radius (centre to ball joint)"},
    {TSE_PARAM_ALPHA_MIN, TSE_PARAM_NAME_ALPHA_MIN, 0, "rad", "0 < alpha_min < pi/2", "scissor angle stop, low"},
    {TSE_PARAM_ALPHA_MIN, TSE_PARAM_NAME_ALPHA_MIN DEG, 1, "deg", "0 < alpha_min_deg < 90",
     "scissor angle stop, low"},
    {TSE_PARAM_ALPHA_MAX, TSE_PARAM_NAME_ALPHA_MAX, 0, "rad", "alpha_min < alpha_max < pi/2",
     "scissor angle stop, high"},
    {TSE_PARAM_ALPHA_MAX, TSE_PARAM_NAME_ALPHA_MAX DEG, 1, "deg", "alpha_min_deg < alpha_max_deg < 90",
     "scissor angle stop, high"},
    {TSE_PARAM_S_MIN, TSE_PARAM_NAME_S_MIN, 0, "m", "s_min >= 0", "slide stroke, low end"},
    {TSE_PARAM_S_MAX, TSE_PARAM_NAME_S_MAX, 0, "m", "s_min < s_max", "slide stroke, high end"},
    {TSE_PARAM_MU_MIN, TSE_PARAM_NAME_MU_MIN, 0, "", "0 <= mu_min < 1", "type-1 singularity margin"},
    {TSE_PARAM_NU_MIN, TSE_PARAM_NAME_NU_MIN, 0, "", "0 <= nu_min < 1", "type-2 singularity margin"},
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

const char *kin_param_key(tse_param_id id)
{
    const kin_param_key_def *k = key_of(id, 0);
    return k ? k->key : "?";
}

int kin_param_is_controller_only(const char *name)
{
    param_key k;
    return param_lookup(name, &k) == 0 && k.id > (int)fw_param_of_kin(TSE_PARAM_COUNT - 1);
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


void kin_params_to_tse(const kin_param_values *p, tse_params *t)
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

/* The controller's set that *p stands for: its kinematic values rounded to the wire's integers
 * (the prototype's are the controller's defaults), the others the controller's defaults.  A design
 * beyond the wire's ranges (L = 1e39) has no such set: it is only scanned, never judged by it. */
static void base_set(const kin_param_values *p, fw_param_set *s)
{
    fw_params_default(s);
    for (int id = TSE_PARAM_L; id < TSE_PARAM_COUNT; ++id) {
        param_key k;
        const int fid = (int)fw_param_of_kin((tse_param_id)id);
        param_si_key(fid, &k);
        const double raw = round(p->v[id] * k.per_unit);
        s->v[fid] = raw >= (double)INT32_MIN && raw <= (double)INT32_MAX ? (int32_t)raw : 0;
    }
}

/* A reading over *p at the built-in rates: tse-kin and tse.kin judge a file as a controller of the
 * built-in rates takes it. */
static void reading_start(const kin_param_values *p, param_reading *r)
{
    fw_param_set base;
    base_set(p, &base);
    param_reading_start(r, &base);
}

/* The reading's kinematic values, where the file set them, over *p. */
static kin_params_outcome adopt(const param_reading *r, const char *name, kin_param_values *p, char *err,
                                size_t errlen)
{
    kin_param_values next = *p;
    for (int id = TSE_PARAM_L; id < TSE_PARAM_COUNT; ++id) {
        const int fid = (int)fw_param_of_kin((tse_param_id)id);
        next.line[id] = r->line[fid];
        next.degrees[id] = r->degrees[fid];
        if (r->line[fid])
            next.v[id] = r->si[fid];
    }
    /* A design is judged here; a controller's set, already judged, keeps these rules (kin_params_file.h). */
    tse_params t;
    kin_params_to_tse(&next, &t);
    const tse_param_id bad = tse_params_check(&t);
    if (bad != TSE_PARAM_OK) {
        kin_params_describe_invalid(&next, bad, name, "", err, errlen);
        return KIN_PARAMS_BAD;
    }
    *p = next;
    return KIN_PARAMS_OK;
}

kin_params_outcome kin_params_parse(const char *text, const char *name, kin_params_judge judge, kin_param_values *p,
                                    char *err, size_t errlen)
{
    char *copy = strdup(text);
    if (!copy) {
        snprintf(err, errlen, "%s: out of memory", name);
        return KIN_PARAMS_UNREADABLE;
    }
    param_reading r;
    reading_start(p, &r);
    const int rc = judge == KIN_PARAMS_DESIGN ? param_text_scan(copy, name, &r, err, errlen)
                                              : param_text_read(copy, name, &r, err, errlen);
    free(copy);
    return rc != 0 ? KIN_PARAMS_BAD : adopt(&r, name, p, err, errlen);
}

kin_params_outcome kin_params_load(const char *path, kin_params_judge judge, kin_param_values *p, char *err,
                                   size_t errlen)
{
    param_reading r;
    reading_start(p, &r);
    const int rc = judge == KIN_PARAMS_DESIGN ? param_file_scan(path, &r, err, errlen)
                                              : param_file_read_full(path, &r, err, errlen);
    if (rc != 0)
        return rc == -2 ? KIN_PARAMS_UNREADABLE : KIN_PARAMS_BAD;
    return adopt(&r, path, p, err, errlen);
}
