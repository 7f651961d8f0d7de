/* The kinematics library behind one precision-neutral interface (double in, double out).
 * kin_ops.c is compiled once per precision and exports kin_ops_double and kin_ops_float, so
 * tse-kin can offer --precision without duplicating any command. */
#ifndef TSE_KIN_OPS_H
#define TSE_KIN_OPS_H

#include "params_file.h"

typedef struct kin_ctx kin_ctx;

typedef struct {
    double ik_cold_ns, ik_warm_ns;       /* median ns per 6-DOF inverse kinematics */
    double iter_cold_mean, iter_warm_mean;
    int iter_cold_max, iter_warm_max;
    long fallbacks_cold, fallbacks_warm;
    double fk_ns;                        /* median ns per forward kinematics, warm */
    int failures;                        /* poses of the trajectory that were not ok */
} kin_bench_result;

typedef struct {
    const char *name;
    kin_ctx *(*create)(const kin_param_values *p); /* NULL for an invalid set */
    void (*destroy)(kin_ctx *c);
    /* Returns the status; q, mu, nu filled as the library reports them. */
    int (*ik)(kin_ctx *c, const double pose[6], const double *seed, double q[6], int *scissor,
              double mu[3], double *nu);
    int (*fk)(kin_ctx *c, const double q[6], const double *seed, double pose[6], int *scissor);
    /* dq/dp at the pose (solved from home) and the singular values of dp/dq, descending. */
    int (*jacobian)(kin_ctx *c, const double pose[6], double J[36], double sv[6], int *scissor);
    int (*sigma_z)(kin_ctx *c, double z, double *sigma);
    int (*haf)(kin_ctx *c, double z, double *haf);
    int (*workspace)(kin_ctx *c, int nr, int nphi, int nz, const double orient[3], long *reach, long *total);
    /* Times the library on n poses of a smooth trajectory: batches, repeats, medians. */
    void (*bench)(kin_ctx *c, const double (*poses)[6], int n, int repeats, kin_bench_result *out);
} kin_ops;

extern const kin_ops kin_ops_double;
extern const kin_ops kin_ops_float;

#endif
