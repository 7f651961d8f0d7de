/* Design parameters and limits of a TSE (kinematics.md, "Design parameters").
 *
 * Angles are in radians here; only the parameter file speaks degrees. */
#ifndef TSE_PARAMS_H
#define TSE_PARAMS_H

#include "tse/real.h"

typedef struct {
    tse_real L;         /* total scissor length [m] */
    tse_real k1;        /* l0 / L */
    tse_real eta;       /* slide angle from the local x axis [rad] (k2) */
    tse_real k3;        /* r_act / L */
    tse_real k4;        /* r_top / L */
    tse_real alpha_min; /* scissor angle stops [rad] */
    tse_real alpha_max;
    tse_real s_min;     /* slide stroke [m] */
    tse_real s_max;
    tse_real mu_min;    /* type-1 singularity margin threshold */
    tse_real nu_min;    /* type-2 (Hadamard ratio) threshold */
} tse_params;

/* Which parameter is wrong.  Precision independent; the values index tse_param_name. */
typedef enum {
    TSE_PARAM_OK = 0,
    TSE_PARAM_L,
    TSE_PARAM_K1,
    TSE_PARAM_ETA,
    TSE_PARAM_K3,
    TSE_PARAM_K4,
    TSE_PARAM_ALPHA_MIN,
    TSE_PARAM_ALPHA_MAX,
    TSE_PARAM_S_MIN,
    TSE_PARAM_S_MAX,
    TSE_PARAM_MU_MIN,
    TSE_PARAM_NU_MIN,
    TSE_PARAM_COUNT
} tse_param_id;

/* The parameters' names as in kinematics.md, written once: tse_param_name, the controller's
 * parameter table (fw_param_table) and the parameter files' keys all spell them from here. */
#define TSE_PARAM_NAME_L "L"
#define TSE_PARAM_NAME_K1 "k1"
#define TSE_PARAM_NAME_ETA "eta"
#define TSE_PARAM_NAME_K3 "k3"
#define TSE_PARAM_NAME_K4 "k4"
#define TSE_PARAM_NAME_ALPHA_MIN "alpha_min"
#define TSE_PARAM_NAME_ALPHA_MAX "alpha_max"
#define TSE_PARAM_NAME_S_MIN "s_min"
#define TSE_PARAM_NAME_S_MAX "s_max"
#define TSE_PARAM_NAME_MU_MIN "mu_min"
#define TSE_PARAM_NAME_NU_MIN "nu_min"

/* Name of the parameter (TSE_PARAM_NAME_*); "?" if unknown. */
const char *tse_param_name(tse_param_id id);

#define tse_params_default TSE_NS(tse_params_default)
#define tse_params_check TSE_NS(tse_params_check)

/* The prototype of the paper, section VI, with the limits of kinematics.md. */
void tse_params_default(tse_params *p);

/* First invalid parameter in the order of tse_param_id, or TSE_PARAM_OK.  Rules (kinematics.md):
 * L > 0, 0 < k1 <= 1, |eta| < 90 deg, k3 >= 0, k4 > 0, 0 < alpha_min < alpha_max < 90 deg,
 * 0 <= s_min < s_max, 0 <= mu_min < 1, 0 <= nu_min < 1; NaN or infinity is invalid everywhere. */
tse_param_id tse_params_check(const tse_params *p);

#endif
