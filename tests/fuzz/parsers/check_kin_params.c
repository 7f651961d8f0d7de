/* tse-kin's parameter file (kin_params_file.h) against its rules read independently: the values an
 * accepted file gives, the line a refused one is refused at, and a refused file's output left as
 * it was. */
#define _POSIX_C_SOURCE 200809L /* fmemopen */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "checks.h"
#include "fuzz_target.h"
#include "fw/params.h"
#include "kin_params_file.h"
#include "ref_text.h"

static const double PI = 3.14159265358979323846;
static const char NAME[] = "fuzz.params";

/* The kinematic spellings kin_params_file.h lists. */
static const struct {
    const char *key;
    tse_param_id id;
    int degrees;
} kin_keys[] = {
    {"L", TSE_PARAM_L, 0},
    {"k1", TSE_PARAM_K1, 0},
    {"eta", TSE_PARAM_ETA, 0},
    {"eta_deg", TSE_PARAM_ETA, 1},
    {"k3", TSE_PARAM_K3, 0},
    {"k4", TSE_PARAM_K4, 0},
    {"alpha_min", TSE_PARAM_ALPHA_MIN, 0},
    {"alpha_min_deg", TSE_PARAM_ALPHA_MIN, 1},
    {"alpha_max", TSE_PARAM_ALPHA_MAX, 0},
    {"alpha_max_deg", TSE_PARAM_ALPHA_MAX, 1},
    {"s_min", TSE_PARAM_S_MIN, 0},
    {"s_max", TSE_PARAM_S_MAX, 0},
    {"mu_min", TSE_PARAM_MU_MIN, 0},
    {"nu_min", TSE_PARAM_NU_MIN, 0},
};
enum { N_KIN_KEYS = sizeof kin_keys / sizeof kin_keys[0] };

static int kin_key(const char *key, size_t len)
{
    for (int i = 0; i < N_KIN_KEYS; ++i)
        if (strlen(kin_keys[i].key) == len && !memcmp(kin_keys[i].key, key, len))
            return i;
    return -1;
}

/* The controller's names that are not kinematic keys, by table index. */
static int controller_key(const char *key, size_t len)
{
    if (kin_key(key, len) >= 0)
        return -1;
    for (int i = 0; i < FP_COUNT; ++i)
        if (strlen(fw_param_table[i].name) == len && !memcmp(fw_param_table[i].name, key, len))
            return i;
    return -1;
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

/* The file by the rules, over base: returns the line it is refused at, 0 for a refusal that names
 * no line, or -1 when it is accepted (with the values in *out). */
static int ref_kin_params(const char *data, size_t size, const kin_param_values *base, kin_param_values *out)
{
    if (memchr(data, '\0', size))
        return 0;
    *out = *base;
    memset(out->line, 0, sizeof out->line);
    memset(out->degrees, 0, sizeof out->degrees);
    int controller_line[FP_COUNT] = {0};
    size_t i = size >= 3 && !memcmp(data, "\xEF\xBB\xBF", 3) ? 3 : 0;
    for (int lineno = 1; i < size; ++lineno) {
        const char *nl = memchr(data + i, '\n', size - i);
        size_t len = (nl ? (size_t)(nl - data) : size) - i;
        const char *line = data + i;
        i += len + 1;
        if (len > KIN_PARAMS_MAX_LINE) /* "longest line in it" */
            return lineno;
        const char *hash = memchr(line, '#', len);
        if (hash)
            len = (size_t)(hash - line);
        line = ref_trim(line, &len);
        if (len == 0)
            continue;
        const char *eq = memchr(line, '=', len);
        if (!eq)
            return lineno;
        size_t klen = (size_t)(eq - line), vlen = len - klen - 1;
        const char *key = ref_trim(line, &klen), *val = ref_trim(eq + 1, &vlen);
        double x;
        const int ctl = controller_key(key, klen);
        if (ctl >= 0) {
            if (controller_line[ctl] || !ref_finite_number(val, vlen, &x))
                return lineno;
            controller_line[ctl] = lineno;
            continue;
        }
        const int k = kin_key(key, klen);
        if (k < 0)
            return lineno;
        const tse_param_id id = kin_keys[k].id;
        if (out->line[id] || !ref_finite_number(val, vlen, &x))
            return lineno;
        out->v[id] = kin_keys[k].degrees ? x * (PI / 180.0) : x;
        out->line[id] = lineno;
        out->degrees[id] = kin_keys[k].degrees;
    }
    tse_params t;
    to_tse(out, &t);
    const tse_param_id bad = tse_params_check(&t);
    return bad == TSE_PARAM_OK ? -1 : out->line[bad];
}

/* A base that is not the defaults, so that "untouched" is told from "reset to defaults". */
static void other_base(kin_param_values *p)
{
    kin_params_default(p);
    p->v[TSE_PARAM_L] = 1.9;
    p->v[TSE_PARAM_K1] = 0.3;
    p->v[TSE_PARAM_ETA] = 0.4;
    p->v[TSE_PARAM_S_MAX] = 0.8;
    p->v[TSE_PARAM_MU_MIN] = 0.1;
    p->v[0] = 12345.678; /* index 0 is unused: it must come back as it went in */
}

static kin_params_outcome parse(const char *data, size_t size, kin_param_values *p, char *err, size_t cap)
{
    if (size == 0) /* fmemopen needs a byte */
        return kin_params_parse("", NAME, p, err, cap);
    FILE *f = fmemopen((void *)data, size, "rb");
    FUZZ_CHECK(f != NULL);
    const kin_params_outcome r = kin_params_parse_stream(f, NAME, p, err, cap);
    fclose(f);
    return r;
}

/* An accepted set printed with %.17g reads back to the same values. */
static void check_reprint(const kin_param_values *p)
{
    char text[2048];
    size_t n = 0;
    for (int id = TSE_PARAM_L; id < TSE_PARAM_COUNT; ++id)
        n += (size_t)snprintf(text + n, sizeof text - n, "%s = %.17g\n", kin_param_key((tse_param_id)id), p->v[id]);
    FUZZ_CHECK(n < sizeof text);
    kin_param_values back;
    kin_params_default(&back);
    char err[512] = "";
    const kin_params_outcome r = kin_params_parse(text, "reprint", &back, err, sizeof err);
    if (r != KIN_PARAMS_OK)
        fprintf(stderr, "%s\n", err);
    FUZZ_CHECK(r == KIN_PARAMS_OK);
    for (int id = TSE_PARAM_L; id < TSE_PARAM_COUNT; ++id)
        FUZZ_CHECK(ref_same_double(back.v[id], p->v[id]));
}

void check_kin_params(const char *data, size_t size, unsigned opt)
{
    kin_param_values p, before, want;
    if (opt & 1)
        other_base(&p);
    else
        kin_params_default(&p);
    before = p;
    const int bad = ref_kin_params(data, size, &before, &want);

    char err[512];
    memset(err, 'Z', sizeof err);
    const kin_params_outcome r = parse(data, size, &p, err, sizeof err);
    if (bad >= 0) {
        FUZZ_CHECK(r == KIN_PARAMS_BAD);
        FUZZ_CHECK(!memcmp(&p, &before, sizeof p));
        FUZZ_CHECK(message_line(err, sizeof err, NAME) == bad);
        return;
    }
    FUZZ_CHECK(r == KIN_PARAMS_OK);
    FUZZ_CHECK(ref_same_double(p.v[0], before.v[0]));
    for (int id = TSE_PARAM_L; id < TSE_PARAM_COUNT; ++id) {
        FUZZ_CHECK(isfinite(p.v[id]));
        FUZZ_CHECK(p.line[id] == want.line[id] && p.degrees[id] == want.degrees[id]);
        if (p.degrees[id]) /* x * pi / 180 however it is grouped */
            FUZZ_CHECK(fabs(p.v[id] - want.v[id]) <= 4 * DBL_EPSILON * fabs(want.v[id]));
        else
            FUZZ_CHECK(ref_same_double(p.v[id], want.v[id]));
    }
    tse_params t;
    to_tse(&p, &t);
    FUZZ_CHECK(tse_params_check(&t) == TSE_PARAM_OK);
    check_reprint(&p);
}
