/* kin-icount (bench/kin_icount.c): the measured operations, one function each, so that callgrind
 * can count a function's inclusive instructions (--toggle-collect=measure_...).
 *
 * kin_icount_prec.c is compiled once per precision; this header is precision-neutral.  Every
 * measure_* function runs its operation `calls` times over the path given to the setup;
 * measure_loop_* runs the same loop with the library call replaced by a stub that does nothing,
 * so that the loop's own cost can be taken off. */
#ifndef KIN_ICOUNT_H
#define KIN_ICOUNT_H

/* Set-up of one precision, outside every measure: the geometry of the default design, the path
 * in that precision, the first warm seed (the cold solution of pose 0), the warm solutions (the
 * forward kinematics' input), and one call of everything measured, so that lazy symbol binding
 * and first-touch costs fall outside the counts.  Returns the poses the warm inverse kinematics
 * rejects (0 expected), or -1 on a set-up error. */
int kin_icount_double_setup(const double (*poses)[6], int n);
int kin_icount_float_setup(const double (*poses)[6], int n);

/* tse_ik seeded with the previous accepted solution: n calls. */
void measure_ik_double_warm(void);
void measure_loop_ik_double_warm(void);
void measure_ik_float_warm(void);
void measure_loop_ik_float_warm(void);
/* tse_ik from home (no seed): n calls. */
void measure_ik_double_cold(void);
void measure_loop_ik_double_cold(void);
void measure_ik_float_cold(void);
void measure_loop_ik_float_cold(void);
/* tse_fk of pose k's slides seeded with pose k - 1: n - 1 calls. */
void measure_fk_double_warm(void);
void measure_loop_fk_double_warm(void);
void measure_fk_float_warm(void);
void measure_loop_fk_float_warm(void);

#endif
