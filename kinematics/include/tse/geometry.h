/* Geometry derived once from validated parameters: the frames of kinematics.md ("Frames") and the
 * constants the solvers need.  Read-only after tse_geometry_init; no global state. */
#ifndef TSE_GEOMETRY_H
#define TSE_GEOMETRY_H

#include "tse/params.h"

/* Index of a pose component in tse_real pose[6]. */
enum { TSE_X = 0, TSE_Y, TSE_Z, TSE_ROLL, TSE_PITCH, TSE_YAW };

typedef struct {
    tse_real er[2];     /* radial unit vector (cos beta, sin beta) */
    tse_real o[2];      /* slide origin O_i = r_act e_r (z = 0) */
    tse_real a[2];      /* slide direction of A: cos(eta) e_t + sin(eta) e_r */
    tse_real b[2];      /* slide direction of B: -cos(eta) e_t + sin(eta) e_r */
} tse_scissor_frame;

typedef struct {
    tse_params p;
    tse_real l0, r_act, r_top;
    tse_real inv_r_top;   /* weighs rotation columns as ball-joint travel in metres */
    tse_real g;           /* (1 - (L/l0)^2) / 4 */
    tse_real c;           /* cos(2 eta) */
    tse_real w_lo, w_hi;  /* base width at alpha_max and alpha_min: w_lo <= w <= w_hi is in the stops */
    /* The same band on w^2, without a square root: w_lo2 <= w^2 <= w_hi2 exactly when the rounded
     * sqrt(w^2) lies in [w_lo, w_hi], so both forms give one verdict. */
    tse_real w_lo2, w_hi2;
    tse_real step_max;    /* Newton step bound [m] */
    /* Squared step lengths [m^2] of the Newton solvers (kinematics/src/scissor_core.h and fk.c say
     * what each decides), and L^2: derived once here rather than on every solve. */
    tse_real newton_acc2, newton_regime2, newton_max2;
    tse_real L2;
    tse_real reach2;      /* |C - O|^2 beyond which a scissor has no physical solution [m^2] */
    /* [m^2]: mu computed at the solver's slides is within mu_guard / (mu n_min) of mu at the exact
     * ones (tse_scissor_solution.n_min), so the type-1 check asks mu_guard of that much room
     * (kinematics/src/scissor_core.h, scissor_mu_clear). */
    tse_real mu_guard;
    tse_real home_pose[6];/* symmetric home: X = Y = 0, zero orientation, mid-range height */
    tse_real home_s;      /* every slide at home */
    tse_scissor_frame sc[3];
} tse_geometry;

#define tse_geometry_init TSE_NS(tse_geometry_init)
#define tse_vertical_slide TSE_NS(tse_vertical_slide)

/* Validates p and fills g.  Returns the first invalid parameter (g untouched) or TSE_PARAM_OK. */
tse_param_id tse_geometry_init(tse_geometry *g, const tse_params *p);

/* Closed-form slide position for the pose (0, 0, z, 0, 0, 0): all six slides are equal there.
 * Returns NaN when the height has no solution on the physical branch. */
tse_real tse_vertical_slide(const tse_geometry *g, tse_real z);

#endif
