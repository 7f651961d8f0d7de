/* tsectl path --plot FILE.png: the plan drawn before anything is sent: the plate's path from above
 * and its height, and each slide's speed row by row against the speed limit in effect.  Drawn by
 * Debian's python3 with matplotlib (python3-matplotlib, scripts/setup.sh), fed the figures on a
 * pipe. */
#ifndef TSECTL_PATH_PLOT_H
#define TSECTL_PATH_PLOT_H

#include <stddef.h>

#include "fw/limits.h"
#include "fw/params.h"
#include "plan/plan.h"

/* Whether the plot can be drawn here (python3 with matplotlib).  0, or -1 with why in err. */
int path_plot_available(char *err, size_t errlen);

/* Draws plan p (planned under set s at rates r) into png.  0, or -1 with why in err. */
int path_plot(const plan *p, const fw_param_set *s, fw_rates r, const char *png, char *err, size_t errlen);

#endif
