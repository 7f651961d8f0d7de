#include "fk_oracle.h"

#include <string.h>

#include "tse/fk.h"
#include "tse/geometry.h"
#include "tse/ik.h"

#if TSE_REAL_FLOAT
#error "the FK oracle is the double-precision kinematics: build it with TSE_REAL_FLOAT=0"
#endif

/* The last geometry built, kept: the parameters change seldom, poses every telemetry period. */
static int64_t last[FK_ORACLE_PARAMS];
static tse_geometry geom;
static int have;

static int geometry(const int64_t k[FK_ORACLE_PARAMS])
{
    if (have && memcmp(k, last, sizeof last) == 0)
        return 0;
    const double u = 1e-6;
    const tse_params p = {(double)k[0] * u, (double)k[1] * u, (double)k[2] * u, (double)k[3] * u,
                          (double)k[4] * u, (double)k[5] * u, (double)k[6] * u, (double)k[7] * u,
                          (double)k[8] * u, (double)k[9] * u, (double)k[10] * u};
    have = 0;
    if (tse_geometry_init(&geom, &p) != TSE_PARAM_OK)
        return -1;
    memcpy(last, k, sizeof last);
    have = 1;
    return 0;
}

int fk_oracle_pose(const int64_t kin_micro[FK_ORACLE_PARAMS], const double q[6], const double seed[6],
                   double pose[6], double *q_error)
{
    if (geometry(kin_micro) != 0)
        return (int)TSE_INVALID;
    tse_fk_result r;
    const tse_status s = tse_fk(&geom, q, seed, &r);
    *q_error = r.q_error;
    if (s != TSE_OK)
        return (int)s;
    memcpy(pose, r.pose, sizeof r.pose);
    return 0;
}

int fk_oracle_slides(const int64_t kin_micro[FK_ORACLE_PARAMS], const double pose[6], const double seed_q[6],
                     double q[6])
{
    if (geometry(kin_micro) != 0)
        return (int)TSE_INVALID;
    double C[3][3];
    tse_apex_points(&geom, pose, C);
    for (int i = 0; i < 3; ++i) {
        tse_scissor_solution sol;
        const tse_status s = tse_scissor_solve(&geom, i, C[i], seed_q[2 * i], seed_q[2 * i + 1], &sol);
        if (s != TSE_OK)
            return (int)s;
        q[2 * i] = sol.s_a;
        q[2 * i + 1] = sol.s_b;
    }
    return 0;
}
