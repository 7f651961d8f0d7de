/* A plan's rows through the controller's own validator (host_tools/traj_check: what tsectl checks
 * a file with before sending it), from rest at the first waypoint. */
#include <string.h>

#include "plan_internal.h"

int plan_validate(plan *p, plan_result *r)
{
    const double *pose0 = p->wp[0].pose;
    if (traj_checker_start(&p->chk, &p->set, p->opt.rates, pose0, p->q0) != 0) {
        r->status = PLAN_PARAMS;
        return 1;
    }
    plan_cursor c;
    plan_row row;
    int64_t prev = 0;
    long k = 0;
    for (plan_rows_begin(p, &c); plan_rows_next(p, &c, &row); ++k) {
        const int64_t t = (int64_t)(row.t * 1e6 + 0.5);
        if (traj_checker_push(&p->chk, (uint32_t)(t - prev), row.pose, k == p->rows - 1, r->reject) != 0) {
            r->status = PLAN_REFUSED;
            r->row = k;
            return 1;
        }
        prev = t;
    }
    return 0;
}
