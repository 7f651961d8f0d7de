/* The kinematics library behind one precision-neutral interface: doubles in, doubles out.
 *
 * Promise: kin_ops.c and kin_bench.c are compiled once per precision (TSE_REAL_FLOAT 0 and 1) and
 * each copy exports its own table, kin_ops_double or kin_ops_float, which calls the library build
 * of that precision (tse_kin_d or tse_kin_f).  Inputs are rounded to the build's precision on the
 * way in and results widened on the way out; nothing else is added, so what the commands print is
 * the library's answer.  No global state: a kin_ctx holds one validated design. */
#ifndef TSE_KIN_OPS_H
#define TSE_KIN_OPS_H

#include "kin_params_file.h"
#include "tse/status.h"

typedef struct kin_ctx kin_ctx;

typedef struct {
    tse_status status;
    int scissor;     /* first failing scissor, 0 when ok */
    double q[6];     /* as the library returned them (NaN where it found no solution) */
    int iterations;
    int fallbacks;
} kin_ik_out;

typedef struct {
    tse_status status;
    int scissor;     /* failing scissor of the inverse-kinematics check, 0 when ok */
    double pose[6];  /* NaN unless status is ok: fk never claims a pose it could not verify */
    int iterations;
} kin_fk_out;

typedef struct {
    tse_status status; /* of the inverse kinematics from home, then of tse_jacobian */
    int scissor;
    double J[6][6];    /* dq/dp: rows s_a1..s_b3, columns x, y, z, roll, pitch, yaw */
    double sv[6];      /* singular values of dp/dq, descending */
} kin_jacobian_out;

/* `tse-kin margins`: the contract's answer for a pose beside both singularity margins of its branch
 * solutions, whatever the limits say (tse_margins). */
typedef struct {
    tse_status status; /* tse_ik's, every check of the contract */
    int scissor;
    double mu[3];      /* type-1 margin of each scissor's branch solution (NaN where none) */
    double nu;         /* type-2 ratio (NaN unless all three scissors have a branch solution) */
} kin_margins_out;

/* `tse-kin profile`: tse_vertical_profile at one height. */
typedef struct {
    double sv[6];      /* singular values of dp/dq, descending */
    double sigma_z, mu_min, nu;
} kin_profile_out;

/* Timings of one precision on one trajectory (see kin_bench.c). */
typedef struct {
    double ik_cold_ns, ik_warm_ns, fk_ns; /* median over batches of the mean ns per pose */
    double iter_cold_mean, iter_warm_mean, iter_fk_mean;
    int iter_cold_max, iter_warm_max, iter_fk_max;
    long fallbacks_cold, fallbacks_warm;
    long not_ok_ik, not_ok_fk;            /* trajectory poses that did not come back ok */
} kin_bench_result;

typedef struct {
    const char *name; /* "double" or "float" */
    /* NULL when this build rejects the set (then *bad names the parameter) or memory runs out
     * (then *bad is TSE_PARAM_OK). */
    kin_ctx *(*create)(const kin_param_values *p, tse_param_id *bad);
    void (*destroy)(kin_ctx *c);
    /* seed_q: previous solution, or NULL for home. */
    tse_status (*ik)(const kin_ctx *c, const double pose[6], const double *seed_q, kin_ik_out *out);
    /* seed_pose: previous pose, or NULL for home. */
    tse_status (*fk)(const kin_ctx *c, const double q[6], const double *seed_pose, kin_fk_out *out);
    /* dq/dp at the pose, its slides solved from home. */
    tse_status (*jacobian)(const kin_ctx *c, const double pose[6], kin_jacobian_out *out);
    tse_status (*sigma_z)(const kin_ctx *c, double z, double *sigma);
    tse_status (*haf)(const kin_ctx *c, double z, double *haf);
    /* The workspace of tse_workspace's grid (n_r, n_phi, n_z) at the orientation: the reachable
     * points (tse_workspace_volume's count, tse_workspace's numbers, screened) and the volume of
     * their cells [m^3]. */
    tse_status (*workspace_volume)(const kin_ctx *c, int n_r, int n_phi, int n_z, const double orientation[3],
                                   long *reachable, long *total, double *volume);
    /* The volume of the cell of grid point (i, j, k), any j (tse_workspace_cell_volume) [m^3]. */
    tse_status (*workspace_cell)(const kin_ctx *c, const int grid[3], int i, int k, double *volume);
    /* Grid point (i, j, k) of tse_workspace's grid (tse_workspace_pose, grid = n_r, n_phi, n_z) and
     * tse_ik's answer there without a seed, the answer tse_workspace counts. */
    tse_status (*workspace_point)(const kin_ctx *c, const int grid[3], int i, int j, int k,
                                  const double orientation[3], double pose[6], int *scissor);
    /* All NaN unless the status is ok. */
    tse_status (*profile)(const kin_ctx *c, double z, kin_profile_out *out);
    tse_status (*margins)(const kin_ctx *c, const double pose[6], kin_margins_out *out);
    /* Times ik cold, ik warm and fk on the n poses, `repeats` batches each. */
    int (*bench)(const kin_ctx *c, const double (*poses)[6], int n, int repeats, kin_bench_result *out);
} kin_ops;

extern const kin_ops kin_ops_double;
extern const kin_ops kin_ops_float;

#endif
