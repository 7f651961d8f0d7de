/* One precision of the kinematics library seen from the fuzz target: doubles in, doubles out.
 *
 * kin_side.c is compiled twice, with TSE_REAL_FLOAT=0 (its functions end in _d, tse_kin_d) and
 * with TSE_REAL_FLOAT=1 (_f, tse_kin_f).  Inputs are rounded to the precision on the way in (a
 * double beyond float's range becomes an infinity of its sign), and every result comes back with
 * the inputs as the library held them, so that the reference can be fed exactly those. */
#ifndef FUZZ_KIN_SIDE_H
#define FUZZ_KIN_SIDE_H

enum { SIDE_NPARAMS = 11 }; /* L, k1, eta, k3, k4, alpha_min, alpha_max, s_min, s_max, mu_min, nu_min */

typedef struct {
    int ret;           /* what tse_ik returned */
    int status, scissor;
    double pose[6];    /* the pose as the library held it */
    double seed[6];    /* the seed likewise, when one was given */
    double q[6], mu[3], nu;
} side_ik;

typedef struct {
    int ret;           /* what tse_fk returned */
    int status, scissor;
    double q[6];       /* the slides as the library held them */
    double seed[6];    /* the seed pose likewise, when one was given */
    double pose[6];
} side_fk;

/* Sets the design every later call of this precision uses: returns tse_geometry_init's answer (a
 * tse_param_id; on a refusal the previous design stays).  held gets the values as this precision
 * holds them.  Also checks that tse_geometry_init refuses exactly what tse_params_check does and
 * leaves its geometry untouched when it refuses. */
int side_init_d(const double p[SIDE_NPARAMS], double held[SIDE_NPARAMS]);
int side_init_f(const double p[SIDE_NPARAMS], double held[SIDE_NPARAMS]);

/* The prototype's parameters (tse_params_default) of this precision. */
void side_default_d(double p[SIDE_NPARAMS]);
void side_default_f(double p[SIDE_NPARAMS]);

/* tse_ik of the current design; seed may be NULL (home). */
void side_ik_d(const double pose[6], const double *seed, side_ik *out);
void side_ik_f(const double pose[6], const double *seed, side_ik *out);

/* tse_fk of the current design; seed may be NULL (home). */
void side_fk_d(const double q[6], const double *seed, side_fk *out);
void side_fk_f(const double q[6], const double *seed, side_fk *out);

#endif
