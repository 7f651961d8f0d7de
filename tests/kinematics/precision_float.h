/* The float build of the kinematics seen from a double translation unit (test_precision.c).
 * precision_float.c is compiled with TSE_REAL_FLOAT=1 and links tse_kin_f. */
#ifndef TSE_TEST_PRECISION_FLOAT_H
#define TSE_TEST_PRECISION_FLOAT_H

/* IK of the prototype in float from home; pose and results converted exactly to/from float.
 * Returns the status, fills q[6] and mu[3]. */
int precision_float_ik(const double pose[6], double q[6], double mu[3]);

/* FK of the prototype in float from home; returns the status, fills pose[6]. */
int precision_float_fk(const double q[6], double pose[6]);

/* Size of tse_real in the float build (a check that the build is what it claims). */
int precision_float_real_size(void);

#endif
