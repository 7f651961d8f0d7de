/* The float build behind a double interface, for comparing the two builds in one program. */
#include "tse/ik.h"

int ik_float(const double pose[6], double q[6], double mu[3]);

int ik_float(const double pose[6], double q[6], double mu[3])
{
    tse_params p;
    tse_params_default(&p);
    tse_geometry g;
    tse_geometry_init(&g, &p);
    tse_real pf[6];
    for (int k = 0; k < 6; ++k)
        pf[k] = (tse_real)pose[k];
    tse_ik_result r;
    tse_ik(&g, pf, NULL, &r);
    for (int k = 0; k < 6; ++k)
        q[k] = (double)r.q[k];
    for (int k = 0; k < 3; ++k)
        mu[k] = (double)r.mu[k];
    return r.status;
}
