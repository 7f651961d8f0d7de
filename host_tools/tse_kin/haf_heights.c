/* Default HAF heights and their mean: see haf_heights.h for the promise. */
#include "haf_heights.h"

#include <math.h>

/* At the stops themselves the scissor is at a limit, not inside the workspace: keep this fraction
 * of the range off each end. */
#define HAF_MARGIN 0.05

int kin_haf_default_heights(const kin_param_values *p, double *z)
{
    const double L = p->v[TSE_PARAM_L];
    const double lo = L * sin(p->v[TSE_PARAM_ALPHA_MIN]), hi = L * sin(p->v[TSE_PARAM_ALPHA_MAX]);
    for (int i = 0; i < KIN_HAF_DEFAULT_HEIGHTS; ++i)
        z[i] = lo + (hi - lo) * (HAF_MARGIN + (1.0 - 2.0 * HAF_MARGIN) * i / (KIN_HAF_DEFAULT_HEIGHTS - 1));
    return KIN_HAF_DEFAULT_HEIGHTS;
}

double kin_haf_mean(const kin_ops *ops, const kin_ctx *ctx, const double *z, int n, int *count)
{
    double sum = 0;
    int k = 0;
    for (int i = 0; i < n; ++i) {
        double h;
        if (ops->haf(ctx, z[i], &h) != TSE_OK || !isfinite(h))
            continue;
        sum += h;
        ++k;
    }
    if (count)
        *count = k;
    return k > 0 ? sum / k : (double)NAN;
}
