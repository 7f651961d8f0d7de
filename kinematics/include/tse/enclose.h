/* The inverse kinematics over a whole piece of a path at once: a proof, from one solution at the
 * piece's centre, that every pose of the piece has exactly one branch solution in a box around it,
 * that the box passes every check of the contract, and how fast the slides can move there.
 *
 * A piece is a stretch of a path whose plate position moves along a straight line and whose
 * orientation turns about a fixed world axis at a constant rate, both linear in a path parameter u
 * (a straight move with slerp, as the controller plans them): P(u) = P_c + lin (u - u_c), and
 * R(u) = exp((u - u_c) [omega]) R_c.  Then every ball joint C_i(u) = P(u) + R(u) r_top e_i obeys
 *     |C_i' | <= |lin| + |omega| r_top,  |C_i'(u) - C_i'(u_c)| <= |omega|^2 r_top |u - u_c|,
 *     |C_i''| <= |omega|^2 r_top,        |C_i''(u) - C_i''(u_c)| <= |omega|^3 r_top |u - u_c|,
 * so over the piece each ball joint stays within rho = (|lin| + |omega| r_top) h of its centre
 * position (h the half-length in u), and the constraints of its scissor, quadratic in the slides
 * and the ball joint, can be bounded over a box by hand-derived interval arithmetic.
 *
 * The argument, per scissor (kinematics.md's F1, F2 and M = dF/ds):
 * - Existence and uniqueness.  With Y = M(x_c)^-1 at the centre solution x_c and a box
 *   X = x_c + [-r, r], the Krawczyk operator K(X) = x_c - Y F(x_c, C) + (I - Y M(X, C))(X - x_c)
 *   is enclosed by x_c + [-kappa, kappa], kappa = |Y F(x_c, C)| + |Y| dM(r) r, for every ball
 *   joint C of the piece.  kappa < r componentwise proves that F(., C) has exactly one zero in X
 *   for each such C (Krawczyk's theorem), and M is nonsingular on X.  By the implicit function
 *   theorem that zero is a continuous function of u: the branch.  Pieces that share an end share
 *   its solution, so a chain of pieces from the start pose's slides follows one branch.
 * - The checks.  Over X and the ball joints' ball: C_z > 0 (below), the base width's square in
 *   [w_lo^2, w_hi^2] (the alpha stops), X inside the stroke, det M >= mu_min |row1| |row2| with the
 *   determinant bounded below and the row norms above (type 1, with the room tse_ik leaves for its
 *   slides' error at the least mu and the shortest row), and the type-2 ratio: a Hadamard
 *   ratio of rows normalised to length one changes by at most the sum of its rows' changes (the
 *   determinant is multilinear in rows and a matrix of unit rows has |det| <= 1), and a row of
 *   length n changed by e gives a unit row changed by at most 2 e / n.
 * - The slides' speed and acceleration along u: M q' = -F_C C' and, differentiated once more,
 *   M q'' = -(M' q' + F_C' C' + F_C C''), all polynomial in (q, q', C, C', C''), bounded over the
 *   box in midpoint-radius arithmetic (which shrinks to the exact value as the piece shrinks).
 * Rounding: every midpoint-radius operation widens its radius by 2 eps of its midpoint, and the
 * centre residual and ratios carry a pad of a few eps of their terms' size; the caller pads the
 * ball joints for the rounding of the poses it evaluates.
 *
 * Nothing here depends on time: a caller multiplies by the path parameter's speed and
 * acceleration. */
#ifndef TSE_ENCLOSE_H
#define TSE_ENCLOSE_H

#include "tse/ik.h"

typedef struct {
    tse_real lin[3];   /* dP/du [m]: constant along the piece */
    tse_real omega[3]; /* world angular velocity d(theta)/du [rad]: constant along the piece */
    tse_real half;     /* half-length of the piece in u (>= 0) */
    tse_real pad;      /* extra ball-joint radius for the rounding of the caller's poses [m] */
} tse_piece;

typedef struct {
    int enclosed;       /* 1: every pose of the piece has one branch solution in [q_lo, q_hi] */
    int proven;         /* 1: enclosed, and the whole box passes every check of the contract */
    int scissor;        /* first scissor whose box could not be enclosed or proven, else 0 */
    tse_status status;  /* TSE_OK when proven; else the first check of the contract that the box of
                         * `scissor` fails (TSE_BELOW .. TSE_DEGENERATE), TSE_SINGULAR when it could
                         * not be enclosed (its constraint matrix too near singular over the piece
                         * for one branch to be told), TSE_INVALID for a centre not solved */
    tse_real q_lo[6], q_hi[6];
    tse_real dq[6];     /* sup |dq_k/du| over the piece (enclosed only) */
    tse_real ddq[6];    /* sup |d2q_k/du2| over the piece (enclosed only) */
    tse_real dq_c[6];   /* dq_k/du at the centre pose itself (enclosed only) */
    tse_real ddq_c[6];  /* d2q_k/du2 at the centre pose itself (enclosed only) */
} tse_enclosure;

#define tse_ik_enclose TSE_NS(tse_ik_enclose)

/* pose: the piece's centre pose; centre: tse_ik's result there, TSE_OK (anything else encloses
 * nothing).  Returns out->proven. */
int tse_ik_enclose(const tse_geometry *g, const tse_piece *piece, const tse_real pose[6],
                   const tse_ik_result *centre, tse_enclosure *out);

#endif
