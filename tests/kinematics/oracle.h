/* Independent reference solution of the TSE kinematics, written from kinematics.md alone.
 *
 * Everything is long double (64-bit mantissa on x86-64) and shares no code with the library:
 * its own frames, its own constraint equations, every solution of each scissor from the quartic
 * in m = a + b (kinematics.md, "Notes for the solver") found by Durand-Kerner iteration in complex
 * long double, then polished by Newton on the original 2x2 system (F1, F2), and its own status
 * classification of a pose.  It knows the status enumeration (tse/status.h, a plain enum) only to
 * speak the same numbers. */
#ifndef TSE_TEST_ORACLE_H
#define TSE_TEST_ORACLE_H

typedef long double orc_real;

typedef struct {
    orc_real L, k1, eta, k3, k4;
    orc_real alpha_min, alpha_max, s_min, s_max, mu_min, nu_min;
} orc_params;

typedef struct {
    orc_params p;
    orc_real l0, r_act, r_top, g, c;
    orc_real cb[3], sb[3];  /* cos beta_i, sin beta_i */
    orc_real O[3][3];       /* slide origins (z = 0) */
    orc_real a[3][3];       /* slide directions of A and B */
    orc_real b[3][3];
} orc_geom;

/* One solution of a scissor's (F1, F2) system. */
typedef struct {
    orc_real sa, sb;
    orc_real det;   /* det M */
    orc_real mu;    /* det M / (|row1| |row2|) */
    orc_real row2;  /* the smaller of |row1|^2, |row2|^2 */
    orc_real w;     /* base width */
    orc_real resid; /* |F1| + |F2| after polishing */
} orc_sol;

#define ORC_MAX_SOL 4

typedef struct {
    int n_real;            /* distinct real solutions found */
    orc_sol real[ORC_MAX_SOL];
    int n;                 /* of those, on the branch: det M > 0, s_A > 0, s_B > 0 */
    orc_sol branch[ORC_MAX_SOL];
    int near_boundary;     /* branch membership of some root is uncertain at the given tolerances */
} orc_scissor_set;

/* How close to a threshold a quantity must be for the outcome to count as uncertain. */
typedef struct {
    orc_real len; /* m: slides against the stroke, C.z against 0, slides against 0 */
    orc_real ang; /* rad: alpha against its stops */
    orc_real mu;  /* mu against mu_min and det M against 0 */
    /* and further from mu_min by mu_noise span^2 / (mu row2), span = L + r_act + r_top: solved in
     * a working precision of epsilon eps, the slides carry the rounding of F's terms (of size
     * span^2) through M's inverse, which turns M's shorter row by up to their error over its length
     * and so moves mu; a few eps span^2 / (mu row2) where M is well conditioned, and without
     * bound where a row vanishes (a scissor's bifurcation) */
    orc_real mu_noise;
    orc_real nu;  /* nu against nu_min */
} orc_tol;

typedef struct {
    int status;       /* the contract's status: the first failing scissor's first failing check */
    int scissor;      /* 1..3, 0 when ok or for degenerate */
    int st[3];        /* first failing check of each scissor on its own (TSE_OK if none) */
    orc_real q[6];    /* chosen branch solution (NaN where none) */
    orc_real mu[3];
    orc_real w[3];
    orc_real alpha[3];
    orc_real nu;      /* NaN unless all three scissors have a branch solution */
    orc_real C[3][3];
    int nsol[3];      /* branch solutions per scissor */
    int ambiguous;    /* some checked quantity lies within the tolerance of its threshold */
    int multi;        /* some scissor has more than one branch solution */
} orc_result;

void orc_geom_init(orc_geom *g, const orc_params *p);

/* R = Rz(yaw) Ry(pitch) Rx(roll) */
void orc_rotation(orc_real roll, orc_real pitch, orc_real yaw, orc_real R[3][3]);
/* roll, pitch, yaw of R (pitch in [-pi/2, pi/2]) */
void orc_rpy(const orc_real R[3][3], orc_real *roll, orc_real *pitch, orc_real *yaw);

void orc_joints(const orc_geom *g, const orc_real pose[6], orc_real C[3][3]);

/* F1, F2 of scissor i (0-based) and its 2x2 Jacobian M. */
void orc_residual(const orc_geom *g, int i, const orc_real C[3], orc_real sa, orc_real sb,
                  orc_real F[2], orc_real M[2][2]);

/* Every real solution of scissor i for ball joint C, and those on the branch (largest mu first). */
void orc_scissor(const orc_geom *g, int i, const orc_real C[3], const orc_tol *tol,
                 orc_scissor_set *out);

/* dF/dp (rotation columns divided by r_top, as kinematics.md weighs them for nu). */
void orc_constraint_jacobian(const orc_geom *g, const orc_real pose[6], const orc_real q[6],
                             orc_real Fp[6][6]);
/* |det A| / prod(row norms) of a 6x6 matrix, by Gaussian elimination with partial pivoting. */
orc_real orc_hadamard(const orc_real A[6][6]);

/* Full classification of a pose.  prefer_q (may be NULL) selects among several branch solutions
 * of a scissor the one nearest to it; without it the one of largest mu is taken. */
void orc_ik(const orc_geom *g, const orc_real pose[6], const orc_real *prefer_q, const orc_tol *tol,
            orc_result *out);

/* Closed form on the vertical axis (X = Y = 0, zero orientation): the slide s with s_A = s_B = s
 * for height z, on the branch; NaN if none (derivation in oracle.c). */
orc_real orc_vertical_slide(const orc_geom *g, orc_real z);

#endif
