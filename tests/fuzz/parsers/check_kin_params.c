/* tse-kin's parameter file (kin_params_file.h) against the one reader it promises to follow: a
 * file is accepted exactly when param_text_read accepts it over the same set, with the same
 * message when refused (and the output left as it was); an accepted file's kinematic values are
 * the written ones, which round to the reader's integers and keep the library's rules. */
#define _POSIX_C_SOURCE 200809L /* strndup */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "checks.h"
#include "fuzz_target.h"
#include "fw/params.h"
#include "kin_params_file.h"
#include "param_text.h"
#include "ref_text.h"

static const char NAME[] = "fuzz.params";

/* The controller's set a kinematic base stands for: its values in micro-units, rounded. */
static void base_set(const kin_param_values *p, fw_param_set *s)
{
    fw_params_default(s);
    for (int id = TSE_PARAM_L; id < TSE_PARAM_COUNT; ++id)
        s->v[FP_L + id - TSE_PARAM_L] = (int32_t)lround(p->v[id] * 1e6);
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

/* An accepted set printed with %.17g reads back to the same values. */
static void check_reprint(const kin_param_values *p, kin_params_judge judge)
{
    char text[2048];
    size_t n = 0;
    for (int id = TSE_PARAM_L; id < TSE_PARAM_COUNT; ++id)
        n += (size_t)snprintf(text + n, sizeof text - n, "%s = %.17g\n", kin_param_key((tse_param_id)id), p->v[id]);
    FUZZ_CHECK(n < sizeof text);
    kin_param_values back;
    kin_params_default(&back);
    char err[512] = "";
    const kin_params_outcome r = kin_params_parse(text, "reprint", judge, &back, err, sizeof err);
    if (r != KIN_PARAMS_OK)
        fprintf(stderr, "%s\n", err);
    FUZZ_CHECK(r == KIN_PARAMS_OK);
    for (int id = TSE_PARAM_L; id < TSE_PARAM_COUNT; ++id)
        FUZZ_CHECK(ref_same_double(back.v[id], p->v[id]));
}

void check_kin_params(const char *data, size_t size, unsigned opt)
{
    kin_param_values p, before;
    if (opt & 1)
        other_base(&p);
    else
        kin_params_default(&p);
    const kin_params_judge judge = opt & 2 ? KIN_PARAMS_DESIGN : KIN_PARAMS_CONTROLLER;
    before = p;
    /* A NUL ends the text a string reader sees: the file reader refuses such a file (test_cli_params_file). */
    char *text = strndup(data, size);
    FUZZ_CHECK(text != NULL);
    char *mine = strdup(text);
    FUZZ_CHECK(mine != NULL);

    fw_param_set base;
    base_set(&before, &base);
    param_reading r;
    param_reading_start(&r, &base);
    char want[512], err[512];
    memset(err, 'Z', sizeof err);
    const int verdict = judge == KIN_PARAMS_DESIGN ? param_text_scan(mine, NAME, &r, want, sizeof want)
                                                   : param_text_read(mine, NAME, &r, want, sizeof want);
    const kin_params_outcome got = kin_params_parse(text, NAME, judge, &p, err, sizeof err);
    free(mine);
    free(text);
    if (verdict != 0 || got != KIN_PARAMS_OK) {
        FUZZ_CHECK(got == KIN_PARAMS_BAD);
        FUZZ_CHECK(!memcmp(&p, &before, sizeof p));
        /* The reader's refusal word for word; beyond it only a design's own rules refuse. */
        FUZZ_CHECK(verdict != 0 ? !strcmp(err, want) : judge == KIN_PARAMS_DESIGN && strstr(err, "is invalid"));
        return;
    }
    FUZZ_CHECK(ref_same_double(p.v[0], before.v[0]));
    for (int id = TSE_PARAM_L; id < TSE_PARAM_COUNT; ++id) {
        const int fid = FP_L + id - TSE_PARAM_L;
        FUZZ_CHECK(isfinite(p.v[id]));
        FUZZ_CHECK(p.line[id] == r.line[fid] && p.degrees[id] == r.degrees[fid]);
        if (!p.line[id]) {
            FUZZ_CHECK(ref_same_double(p.v[id], before.v[id]));
            continue;
        }
        /* A controller's set: the written value is the integer's before rounding, within half a
         * unit of it (and a rounding of pi / 180 more in degrees). */
        if (judge == KIN_PARAMS_CONTROLLER)
            FUZZ_CHECK(fabs(p.v[id] * 1e6 - (double)r.set.v[fid]) <= (p.degrees[id] ? 0.5 + 1e-6 : 0.5));
    }
    tse_params t;
    kin_params_to_tse(&p, &t);
    FUZZ_CHECK(tse_params_check(&t) == TSE_PARAM_OK);
    check_reprint(&p, judge);
}
