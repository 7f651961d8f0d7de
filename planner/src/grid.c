/* The path's kinematics over the grid: every waypoint, then every grid point, solved as the
 * controller solves a pose (tse_ik: stroke, angle stops, both singularity margins), warm-started
 * along the path as execution runs; the slides' derivatives along s from the Jacobian. */
#include <math.h>
#include <string.h>

#include "plan_internal.h"
#include "tse/ik.h"
#include "tse/jacobian.h"

static void workspace_fault(plan_result *r, const tse_ik_result *ik, int waypoint, bool between, double at)
{
    r->status = PLAN_WORKSPACE;
    r->waypoint = waypoint;
    r->between = between;
    r->at = at;
    r->kin = ik->status;
    r->scissor = ik->scissor;
}

/* The waypoint whose stretch holds s (the last one at or before it). */
static int stretch_of(const plan_path *path, double s)
{
    return (int)plan_interval(path->ws, path->n, s);
}

int plan_grid_solve(plan *p, plan_result *r)
{
    const plan_path *path = &p->path;
    plan_grid *gr = &p->grid;
    tse_ik_result ik;
    /* The waypoints first, so that a waypoint outside is named as itself. */
    const double *seed = NULL;
    double q[6];
    for (int i = 0; i < p->n; ++i) {
        if (tse_ik(&p->g, p->wp[i].pose, seed, &ik) != TSE_OK) {
            workspace_fault(r, &ik, i, false, 0.0);
            return -1;
        }
        memcpy(q, ik.q, sizeof q);
        seed = q;
        if (i == 0)
            memcpy(p->q0, ik.q, sizeof p->q0);
    }
    memcpy(q, p->q0, sizeof q);
    for (long i = 0; i <= gr->N; ++i) {
        const double s = i == gr->N ? path->length : (double)i * gr->h;
        double pose[6], dp[6], ddp[6], J[6][6];
        plan_path_eval(path, s, pose, dp, ddp);
        if (tse_ik(&p->g, pose, q, &ik) != TSE_OK || tse_jacobian(&p->g, pose, ik.q, J) != TSE_OK) {
            if (ik.status == TSE_OK)
                ik.status = TSE_SINGULAR;
            const int w = stretch_of(path, s);
            workspace_fault(r, &ik, w, true, (s - path->ws[w]) / (path->ws[w + 1] - path->ws[w]));
            return -1;
        }
        memcpy(q, ik.q, sizeof q);
        for (int j = 0; j < 6; ++j) {
            double d = 0.0;
            for (int k = 0; k < 6; ++k)
                d += J[j][k] * dp[k];
            gr->qs[i][j] = d;
            double e = 0.0;
            for (int k = 0; k < 6; ++k)
                e += J[j][k] * ddp[k];
            gr->qsj[i][j] = e; /* J p'' for now: q_ss less this below */
        }
        /* The plate speed cap of the stretch, through the plate's speed per unit of s. */
        gr->stretch[i] = stretch_of(path, s);
        const double v = p->wp[gr->stretch[i]].v;
        const double ps = sqrt(dp[0] * dp[0] + dp[1] * dp[1] + dp[2] * dp[2]);
        gr->vcap2[i] = isfinite(v) && ps > 1e-12 ? (v / ps) * (v / ps) : INFINITY;
    }
    /* q_ss by central differences of q_s (one-sided at the ends): J' p' + J p'' without J'. */
    for (long i = 0; i <= gr->N; ++i) {
        const long a = i > 0 ? i - 1 : i, b = i < gr->N ? i + 1 : i;
        const double span = (double)(b - a) * gr->h;
        for (int j = 0; j < 6; ++j) {
            gr->qss[i][j] = (gr->qs[b][j] - gr->qs[a][j]) / span;
            gr->qsj[i][j] = gr->qss[i][j] - gr->qsj[i][j];
        }
    }
    return 0;
}
