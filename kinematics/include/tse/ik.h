/* Inverse kinematics (kinematics.md, "The solution and what makes it valid").
 *
 * Per scissor: Newton on (F1, F2) with bounded steps from a seed; when Newton stalls or lands off
 * the det M > 0 sheet, the quartic in m = a + b enumerates every solution, so a pose is declared
 * unreachable only when no root gives det M > 0 with positive slides. */
#ifndef TSE_IK_H
#define TSE_IK_H

#include "tse/geometry.h"
#include "tse/status.h"

typedef struct {
    tse_real s_a, s_b;
    tse_real det;   /* det M (> 0 on the physical sheet) */
    tse_real mu;    /* type-1 margin: det M / (|row1| |row2|) */
    tse_real n_min; /* the smaller squared norm of M's rows, over 4 [m^2]: how much the slides'
                     * rounding can move mu (tse_geometry.mu_guard) */
    tse_real w;     /* base width */
    int iterations; /* Newton iterations */
    int fallback;   /* 1 when the quartic was needed */
} tse_scissor_solution;

typedef struct {
    tse_status status;
    int scissor;     /* first failing scissor 1..3; 0 when ok */
    tse_real q[6];   /* s_A1, s_B1, s_A2, s_B2, s_A3, s_B3 (NaN where no solution was found) */
    tse_real mu[3];  /* type-1 margin per scissor */
    tse_real nu;     /* type-2 Hadamard ratio (NaN if not reached) */
    tse_real C[3][3];/* ball joints in the world frame */
    int iterations;  /* Newton iterations over the three scissors */
    int fallbacks;   /* scissors that needed the quartic */
} tse_ik_result;

#define tse_apex_points TSE_NS(tse_apex_points)
#define tse_rotation TSE_NS(tse_rotation)
#define tse_scissor_solve TSE_NS(tse_scissor_solve)
#define tse_scissor_residual TSE_NS(tse_scissor_residual)
#define tse_ik TSE_NS(tse_ik)

/* R = Rz(yaw) Ry(pitch) Rx(roll), row-major. */
void tse_rotation(tse_real roll, tse_real pitch, tse_real yaw, tse_real R[3][3]);

/* Ball joints C_i = (X, Y, Z) + r_top R (cos beta_i, sin beta_i, 0). */
void tse_apex_points(const tse_geometry *g, const tse_real pose[6], tse_real C[3][3]);

/* F1, F2 of scissor i (0-based) at slides (s_a, s_b) for ball joint C. */
void tse_scissor_residual(const tse_geometry *g, int i, const tse_real C[3], tse_real s_a,
                          tse_real s_b, tse_real F[2]);

/* Solution of scissor i (0-based) on the physical branch for ball joint C, nearest the seed
 * (seed_a, seed_b) when more than one exists; no limit is checked here.  Returns TSE_OK,
 * TSE_INVALID (non-finite C or seed), TSE_UNREACHABLE or TSE_NOCONVERGE. */
tse_status tse_scissor_solve(const tse_geometry *g, int i, const tse_real C[3], tse_real seed_a,
                             tse_real seed_b, tse_scissor_solution *out);

/* Full 6-DOF inverse kinematics with every check of the contract, in its order.  seed_q is the
 * previous solution (warm start) or NULL for the symmetric home configuration.  The result does
 * not depend on anything but (g, pose, seed_q).  Returns out->status. */
tse_status tse_ik(const tse_geometry *g, const tse_real pose[6], const tse_real seed_q[6],
                  tse_ik_result *out);

#endif
