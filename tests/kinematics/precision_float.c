/* Compiled with TSE_REAL_FLOAT=1: the float side of test_precision (see precision_float.h). */
#include "precision_float.h"

#include "tse/fk.h"
#include "tse/ik.h"
#include "tse/params.h"

_Static_assert(sizeof(tse_real) == sizeof(float), "precision_float.c must be built as float");

static void prototype(tse_geometry *g)
{
    tse_params p;
    tse_params_default(&p);
    (void)tse_geometry_init(g, &p);
}

int precision_float_ik(const double pose[6], double q[6], double mu[3])
{
    tse_geometry g;
    prototype(&g);
    tse_real pf[6];
    for (int k = 0; k < 6; k++)
        pf[k] = (tse_real)pose[k];
    tse_ik_result r;
    tse_ik(&g, pf, NULL, &r);
    for (int k = 0; k < 6; k++)
        q[k] = (double)r.q[k];
    for (int i = 0; i < 3; i++)
        mu[i] = (double)r.mu[i];
    return (int)r.status;
}

int precision_float_fk(const double q[6], double pose[6])
{
    tse_geometry g;
    prototype(&g);
    tse_real qf[6];
    for (int k = 0; k < 6; k++)
        qf[k] = (tse_real)q[k];
    tse_fk_result r;
    tse_fk(&g, qf, NULL, &r);
    for (int k = 0; k < 6; k++)
        pose[k] = (double)r.pose[k];
    return (int)r.status;
}

int precision_float_real_size(void)
{
    return (int)sizeof(tse_real);
}
