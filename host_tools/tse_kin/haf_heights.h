/* The heights at which `tse-kin haf` evaluates the HAF by default, and the mean it reports: shared
 * with `tse-kin sweep`, whose HAF column must be the figure `haf` prints for the same design.
 *
 * Promise: pure (no I/O). */
#ifndef TSE_KIN_HAF_HEIGHTS_H
#define TSE_KIN_HAF_HEIGHTS_H

#include "kin_ops.h"
#include "kin_params_file.h"

/* How many default heights there are. */
enum { KIN_HAF_DEFAULT_HEIGHTS = 9 };

/* Writes the default heights of the design to z[0..KIN_HAF_DEFAULT_HEIGHTS): spread over the alpha
 * stops' heights L sin(alpha_min) .. L sin(alpha_max), 5 % of the range in from either stop.
 * Returns how many. */
int kin_haf_default_heights(const kin_param_values *p, double *z);

/* Mean of ops->haf over the heights z[0..n) that have a value, NaN when none has; *count (may be
 * NULL) is how many had one. */
double kin_haf_mean(const kin_ops *ops, const kin_ctx *ctx, const double *z, int n, int *count);

#endif
