/* Inverse kinematics in fixed point, for a core without a floating-point unit (a Cortex-M3 or
 * M0+): the contract of docs/kinematics.md ("The solution and what makes it valid", the checks in
 * their order, the same statuses), computed in integers only.  A separate implementation beside
 * the float and double builds (tse/ik.h), which it leaves untouched; docs/kinematics.md ("The
 * fixed-point build") gives the formats, their ranges and where the accuracy holds.
 *
 * Formats (int32 unless said):
 *   lengths, positions, slides   Q24 metres   (TSE_FX_M = 2^24 per metre: 59.6 nm, +-128 m)
 *   angles                       Q28 radians  (TSE_FX_RAD = 2^28 per radian: 3.7e-9 rad, +-8 rad)
 *   ratios (k1, k3, k4, mu, nu)  Q30          (TSE_FX_ONE = 2^30)
 * No heap, no global state; the geometry is read-only after tse_fx_geometry_init. */
#ifndef TSE_IK_FIXED_H
#define TSE_IK_FIXED_H

#include <stdint.h>

#include "tse/params.h"
#include "tse/status.h"

#define TSE_FX_M 16777216           /* 2^24: one metre */
#define TSE_FX_RAD 268435456        /* 2^28: one radian */
#define TSE_FX_ONE 1073741824       /* 2^30: one */
#define TSE_FX_NONE INT32_MIN       /* a slide, mu or nu that was not found (the double build's NaN) */

/* The design, in the formats above; the same rules as tse_params_check, and the fixed build's own
 * ranges (tse_fx_geometry_init). */
typedef struct {
    int32_t L, k1, eta, k3, k4, alpha_min, alpha_max, s_min, s_max, mu_min, nu_min;
} tse_fx_params;

typedef struct {
    int32_t o[2];   /* slide origin, Q28 (the ball joints are formed in Q28: see fx_localize) */
    int32_t a[2], b[2]; /* slide directions, Q30 */
} tse_fx_scissor_frame;

typedef struct {
    tse_fx_params p;
    int32_t l0, r_act, r_top;  /* Q24 */
    int32_t r_top28;           /* r_top in Q28: the ball joints' offsets to 4e-9 m */
    int32_t g;                 /* (1 - (L/l0)^2) / 4, Q26 (k1 >= 1/8 keeps it above -16) */
    int32_t c;                 /* cos(2 eta), Q30 */
    int64_t w_lo2, w_hi2;      /* the stops as a band on the base width squared, Q48 */
    int64_t L2;                /* Q48 */
    int64_t reach2;            /* Q48: beyond it a scissor has no physical solution */
    int64_t step_max2;         /* Q48: Newton's step bound, squared */
    int32_t step_max;          /* Q24 */
    int64_t mu_guard;          /* Q48: room the type-1 check leaves for the slides' rounding */
    int32_t s_box;             /* Q24: Newton gives up beyond |s| > s_box (the format's room) */
    int32_t home_s;            /* Q24: every slide at the symmetric home */
    tse_fx_scissor_frame sc[3];
} tse_fx_geometry;

typedef struct {
    tse_status status;
    int scissor;       /* first failing scissor 1..3; 0 when ok */
    int32_t q[6];      /* Q24; TSE_FX_NONE where no solution was found */
    int32_t mu[3];     /* Q30 type-1 margin per scissor (TSE_FX_NONE where none) */
    int32_t nu;        /* Q30 type-2 Hadamard ratio (TSE_FX_NONE if not reached) */
    int32_t C[3][3];   /* ball joints, Q24 (clamped to the format where a pose leaves it) */
    int iterations;    /* Newton iterations over the three scissors */
    int fallbacks;     /* scissors that needed the quartic */
} tse_fx_ik_result;

/* The prototype (tse/prototype.h) in the fixed formats, rounded to nearest. */
void tse_fx_params_default(tse_fx_params *p);

/* Validates p (tse_params_check's rules, then the fixed build's ranges: L <= 4 m, k1 >= 1/8,
 * s_max <= 8 m, r_act and r_top <= 4 m, and a reach, L + 2 l0 sqrt(2 / (1 + cos 2 eta)), of at
 * most 8 m; the first one broken names its parameter) and fills g.  Returns the first invalid
 * parameter (g untouched) or TSE_PARAM_OK. */
tse_param_id tse_fx_geometry_init(tse_fx_geometry *g, const tse_fx_params *p);

/* The full inverse kinematics with every check of the contract in its order.  pose: X, Y, Z in
 * Q24 m, roll, pitch, yaw in Q28 rad (any value: angles wrap).  seed_q: the previous solution
 * (Q24) or NULL for home; a seed beyond the format's room (|s| > s_box) is `invalid`.  The result
 * depends only on (g, pose, seed_q).  Returns out->status. */
tse_status tse_fx_ik(const tse_fx_geometry *g, const int32_t pose[6], const int32_t *seed_q,
                     tse_fx_ik_result *out);

/* sin and cos of an angle in Q28 rad, in Q30 (error below 1e-8; any angle). */
void tse_fx_sincos(int32_t angle, int32_t *s, int32_t *c);

/* floor(sqrt(x)). */
uint32_t tse_fx_isqrt(uint64_t x);

#endif
