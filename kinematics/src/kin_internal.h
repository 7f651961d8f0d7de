/* Helpers shared inside the kinematics library; not part of its contract.  Names go through
 * TSE_NS like the public ones, since the float and double builds may be linked together. */
#ifndef TSE_KIN_INTERNAL_H
#define TSE_KIN_INTERNAL_H

#include "trig.h"
#include "tse/geometry.h"
#include "tse/ik.h"

/* The inverse and forward kinematics in two builds on an x86-64 host (GCC's function
 * multiversioning): the baseline's, and one for a CPU with fused multiply-add (most x86-64 since
 * 2013), whose a * b + c is one instruction rounded once, as on the Cortex-M4F.  The
 * loader picks one when the program starts.  Most of a solve is such products and sums: the
 * second build runs about a third fewer instructions (scripts/kin_icount.sh).  Results differ
 * between the two in the last bits only, within every accuracy the contract states; one machine
 * always runs the same one.  TSE_NO_FMA_CLONES builds only the baseline, as does Clang (14 leaves
 * a cloned function unresolved in other translation units; the fuzz preset builds with it). */
#if defined(__x86_64__) && defined(__ELF__) && defined(__GNUC__) && !defined(__clang__) && \
    !defined(TSE_NO_FMA_CLONES)
#define TSE_FMA_CLONES __attribute__((target_clones("fma", "default")))
/* For a helper of a cloned function: called out of line, it would run the baseline's build. */
#define TSE_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define TSE_FMA_CLONES
#define TSE_ALWAYS_INLINE inline
#endif

/* Whether tse_ik runs the three scissors' first Newton pass side by side (scissor_warm_steps):
 * an out-of-order core overlaps their chains of dependent operations, an in-order one (an
 * M-profile Arm: the board's Cortex-M4) would only pay for the bookkeeping.  The results are the
 * same either way. */
#if defined(__ARM_ARCH_PROFILE) && __ARM_ARCH_PROFILE == 'M'
#define TSE_SIDE_BY_SIDE 0
#else
#define TSE_SIDE_BY_SIDE 1
#endif

/* What the constraints of one scissor need to know of its ball joint. */
typedef struct {
    tse_real d[3]; /* C - O_i */
    tse_real u, v; /* d . a_i, d . b_i */
    tse_real rho2; /* |d|^2 */
} tse_scissor_local;

#define tse_scissor_localize TSE_NS(tse_scissor_localize)
#define tse_scissor_eval TSE_NS(tse_scissor_eval)
#define tse_poly_real_roots TSE_NS(tse_poly_real_roots)
#define tse_plate_frame TSE_NS(tse_plate_frame)
#define tse_apex_from_frame TSE_NS(tse_apex_from_frame)
#define tse_lu_factor6 TSE_NS(tse_lu_factor6)
#define tse_lu_solve6 TSE_NS(tse_lu_solve6)
#define tse_sym_eigen6 TSE_NS(tse_sym_eigen6)
#define tse_weakest_row6 TSE_NS(tse_weakest_row6)
#define tse_constraint_rows TSE_NS(tse_constraint_rows)
#define tse_scissor_solve_local TSE_NS(tse_scissor_solve_local)
#define tse_scissor_fallback TSE_NS(tse_scissor_fallback)
#define tse_newton_limits TSE_NS(tse_newton_limits)

/* Newton iterations a solve from a seed may take before the quartic decides. */
#define TSE_NEWTON_MAX_ITER 40

void tse_scissor_localize(const tse_geometry *g, int i, const tse_real C[3], tse_scissor_local *loc);

/* F = (F1, F2) and M = dF/d(s_A, s_B) at the given slides. */
void tse_scissor_eval(const tse_geometry *g, const tse_scissor_local *loc, tse_real s_a, tse_real s_b,
                      tse_real F[2], tse_real M[2][2]);

/* All real roots of sum coef[k] x^k (deg 1..4, coef[deg] != 0), ascending; returns how many. */
int tse_poly_real_roots(const tse_real *coef, int deg, tse_real *roots);

/* The plate's orientation, computed once per pose from one set of sines and cosines: R, and the
 * world-frame axes about which roll, pitch and yaw turn the plate (R = Rz Ry Rx), so that
 * dR/dtheta_k v = axis_k x (R v).  Axis rows: roll, pitch, yaw. */
typedef struct {
    tse_real R[3][3];
    tse_real axes[3][3];
} tse_plate;

void tse_plate_frame(const tse_real pose[6], tse_plate *f);

/* What the inverse and forward kinematics need of the plate's orientation, from one set of
 * sines and cosines (tse_plate is the general form, for the Jacobian and the cold paths). */
typedef struct {
    tse_real rho[3][3];  /* R e_r_i: unit vector from the plate's centre to ball joint i */
    tse_real N[3];       /* R e_z: the plate's normal */
    tse_real sy, cy, sp, cp; /* sines and cosines of yaw and pitch */
} tse_pose_frame;

/* R = Rz(yaw) Ry(pitch) Rx(roll) as tse_plate_frame, but only the columns the solver uses, and
 * the three directions rho_i = R e_r_i written out for the azimuths 0, 120 and 240 degrees
 * (kinematics.md, "Frames"): with geometry.c's e_r = (1, 0), (-1/2, +-sqrt(3)/2) these are the
 * same products and sums as R e_r, bit for bit, without the multiplications by 1 and 0. */
static TSE_ALWAYS_INLINE void tse_pose_frame_of(const tse_real pose[6], tse_pose_frame *f)
{
    tse_real sr, cr, sp, cp, sy, cy;
    tse_sincos(pose[TSE_ROLL], &sr, &cr);
    tse_sincos(pose[TSE_PITCH], &sp, &cp);
    tse_sincos(pose[TSE_YAW], &sy, &cy);
    const tse_real cysp = cy * sp, sysp = sy * sp;
    const tse_real col0[3] = {cy * cp, sy * cp, -sp};
    const tse_real col1[3] = {cysp * sr - sy * cr, sysp * sr + cy * cr, cp * sr};
    f->N[0] = cysp * cr + sy * sr;
    f->N[1] = sysp * cr - cy * sr;
    f->N[2] = cp * cr;
    for (int k = 0; k < 3; ++k) {
        const tse_real m = TSE_R(-0.5) * col0[k], t = TSE_R(0.86602540378443864676) * col1[k];
        f->rho[0][k] = col0[k];
        f->rho[1][k] = m + t;
        f->rho[2][k] = m - t;
    }
    f->sy = sy;
    f->cy = cy;
    f->sp = sp;
    f->cp = cp;
}

void tse_apex_from_frame(const tse_geometry *g, const tse_real pose[6], const tse_plate *f,
                         tse_real C[3][3]);

/* In-place LU with partial pivoting.  Returns the determinant (0 when a pivot vanishes). */
tse_real tse_lu_factor6(tse_real A[6][6], int perm[6]);
void tse_lu_solve6(const tse_real LU[6][6], const int perm[6], const tse_real b[6], tse_real x[6]);

/* Eigenvalues of a symmetric 6x6 matrix (cyclic Jacobi), descending.  A is destroyed. */
void tse_sym_eigen6(tse_real A[6][6], tse_real eig[6]);

/* Row of a nonsingular matrix closest to the span of the others, after normalising every row:
 * the one whose column of the inverse is longest.  -1 if A is singular. */
int tse_weakest_row6(const tse_real A[6][6]);

/* dF/dp (rows F1_i, F2_i) given the frame and ball joints already computed for pose p, its
 * rotation columns multiplied by rot_scale; and, when M is not NULL, the blocks M_i. */
void tse_constraint_rows(const tse_geometry *g, const tse_real pose[6], const tse_plate *f,
                         const tse_real C[3][3], const tse_real q[6], tse_real rot_scale,
                         tse_real Fp[6][6], tse_real M[3][2][2]);

/* tse_scissor_solve (tse/ik.h) for a ball joint already localized, without its checks of the
 * input: for a caller that has made sure the ball joint and the seed are finite. */
tse_status tse_scissor_solve_local(const tse_geometry *g, const tse_scissor_local *loc,
                                   tse_real seed_a, tse_real seed_b, tse_scissor_solution *out);

/* Fills the newton_* constants and L2 of g from g->p.L and g->step_max (scissor_core.h). */
void tse_newton_limits(tse_geometry *g);

/* The rest of tse_scissor_solve_local once Newton from the seed did not give a physical solution
 * inside the limits: the quartic's enumeration.  (s_a, s_b) is where Newton got to (the seed if it
 * failed), described in out when nothing is found; iterations counts Newton's so far. */
tse_status tse_scissor_fallback(const tse_geometry *g, const tse_scissor_local *loc, tse_real seed_a,
                                tse_real seed_b, tse_real s_a, tse_real s_b, int iterations,
                                tse_scissor_solution *out);

#endif
