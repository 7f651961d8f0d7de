/* Host program, run by the board build: writes the table of poses that the `kinematics` target
 * image checks the float kinematics against (kin_table.h describes it).
 *
 * Built with the host C compiler from the kinematics sources in double precision
 * (TSE_REAL_FLOAT=0).  Poses are drawn from a fixed-seed generator, so the table is the same on
 * every build.  They come in paths (a start, then small random steps), so that the image can run
 * the inverse kinematics warm along each path as well as cold.  A pose enters the table only when
 * its status is decided with margin, so that float, whose rounding moves every quantity a
 * little, is expected to agree:
 *   - every quantity a check compares (ball-joint height, base width, slides, mu, nu) is
 *     farther from its threshold than float could move it;
 *   - the status and failing scissor stay the same when any pose coordinate moves by
 *     +-PERTURB (this covers `unreachable`, which has no quantity to measure);
 *   - the double IK gives the same answer cold and warm (seeded as the image will seed it);
 *   - the solver never gives up (noconverge is never expected).
 * Generation goes on until every status has its quota (stroke needs design 1, whose stroke is
 * tightened; kinematics.md's default stroke lets the alpha stops bound the workspace), and
 * `invalid` comes from explicit non-finite poses.
 *
 * The same table carries what the planner and controller images compare with: reference poses
 * in whole micrometres and microradians with their double slides, and straight paths between
 * accepted poses through a region where the IK fails, with where it first fails (kin_table.h).
 *
 *   gen_kin_table OUTPUT.c */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tse/fk.h"
#include "tse/geometry.h"
#include "tse/ik.h"
#include "tse/jacobian.h"
#include "kin_table.h"

#define MAX_CASES 1200
#define PERTURB 5e-5     /* m or rad: the status must not change within this of the pose (float
                          * moves a ball joint by ~1e-7 m; the singular band is ~1e-4 m wide) */
#define MARGIN_LEN 1e-4  /* m: C.z, w and the slides this far from their thresholds */
#define MARGIN_MU 2e-3   /* mu this far from mu_min */
#define MARGIN_MU_FOLD 5e-3 /* mu at least this */
#define MARGIN_NU 0.1    /* nu this fraction of nu_min away from it */
#define QUOTA 40         /* poses of each status (at least) */
#define QUOTA_SCISSOR 4  /* ... and of each failing status on each scissor */
#define WALK 4           /* poses per random path */

typedef struct {
    int design, path_start;
    tse_ik_result r;
    double pose[6];
    int fk;
    double fk_sens[6];
} entry;

static entry cases[MAX_CASES];
static int ncases;
static float design_f[2][11];
static tse_geometry geom[2];

/* splitmix64: a fixed sequence on every host. */
static uint64_t rng_state = 0x7453455f6b696e21ull;

static double uniform(double lo, double hi)
{
    uint64_t z = (rng_state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return lo + (hi - lo) * ((double)(z >> 11) * (1.0 / 9007199254740992.0));
}

/* Rounds to the float the board's table holds, so both precisions see the same input. */
static double as_float(double x)
{
    return (double)(float)x;
}

static void make_designs(void)
{
    for (int d = 0; d < 2; ++d) {
        tse_params p;
        tse_params_default(&p);
        if (d == 1) {
            /* Slides run about 0.18..0.52 m inside the alpha stops: this stroke cuts through. */
            p.s_min = 0.22;
            p.s_max = 0.45;
        }
        double *v[11] = {&p.L, &p.k1, &p.eta, &p.k3, &p.k4, &p.alpha_min, &p.alpha_max,
                         &p.s_min, &p.s_max, &p.mu_min, &p.nu_min};
        for (int k = 0; k < 11; ++k) {
            design_f[d][k] = (float)*v[k];
            *v[k] = (double)design_f[d][k];
        }
        if (tse_geometry_init(&geom[d], &p) != TSE_PARAM_OK) {
            fprintf(stderr, "gen_kin_table: design %d invalid\n", d);
            exit(1);
        }
    }
}

static int all_finite(const double q[6])
{
    for (int k = 0; k < 6; ++k)
        if (!isfinite(q[k]))
            return 0;
    return 1;
}

static int far_from(double x, double threshold, double margin)
{
    return fabs(x - threshold) >= margin;
}

/* Every compared quantity far from its threshold. */
static int margins_hold(const tse_geometry *g, const tse_ik_result *r)
{
    const tse_params *p = &g->p;
    for (int i = 0; i < 3; ++i) {
        const double sa = r->q[2 * i], sb = r->q[2 * i + 1];
        if (!isfinite(sa) || !isfinite(sb))
            continue;
        const double w = sqrt(sa * sa + sb * sb + 2.0 * g->c * sa * sb);
        if (!far_from(r->C[i][2], 0.0, MARGIN_LEN) || !far_from(w, g->w_lo, MARGIN_LEN) ||
            !far_from(w, g->w_hi, MARGIN_LEN) || !far_from(w, 2.0 * g->l0, MARGIN_LEN))
            return 0;
        if (!far_from(sa, p->s_min, MARGIN_LEN) || !far_from(sa, p->s_max, MARGIN_LEN) ||
            !far_from(sb, p->s_min, MARGIN_LEN) || !far_from(sb, p->s_max, MARGIN_LEN))
            return 0;
        /* mu also stays clear of 0, where the solution folds away (unreachable beyond) */
        if (!far_from(r->mu[i], p->mu_min, MARGIN_MU) || !(r->mu[i] >= MARGIN_MU_FOLD))
            return 0;
    }
    if (isfinite(r->nu) && !far_from(r->nu, p->nu_min, MARGIN_NU * p->nu_min))
        return 0;
    return 1;
}

/* The pose's double result if its status is decided with margin, cold and warm alike. */
static int decided(const tse_geometry *g, const double pose[6], const double *seed, tse_ik_result *out)
{
    tse_ik(g, pose, NULL, out);
    if (out->status == TSE_NOCONVERGE || !margins_hold(g, out))
        return 0;
    if (seed) {
        tse_ik_result w;
        tse_ik(g, pose, seed, &w);
        if (w.status != out->status || w.scissor != out->scissor)
            return 0;
        for (int k = 0; k < 6; ++k) {
            if (isfinite(out->q[k]) != isfinite(w.q[k]))
                return 0;
            if (isfinite(out->q[k]) && fabs(out->q[k] - w.q[k]) > 1e-9)
                return 0;
        }
    }
    for (int k = 0; k < 6; ++k) {
        for (int sgn = -1; sgn <= 1; sgn += 2) {
            double p[6];
            memcpy(p, pose, sizeof p);
            p[k] += sgn * PERTURB;
            tse_ik_result n;
            tse_ik(g, p, NULL, &n);
            if (n.status != out->status || n.scissor != out->scissor)
                return 0;
        }
    }
    return 1;
}

/* Inverse of a 6x6 matrix by Gauss-Jordan with partial pivoting.  Returns 0 if singular. */
static int invert6(const double A[6][6], double inv[6][6])
{
    double m[6][12];
    for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 12; ++j)
            m[i][j] = j < 6 ? A[i][j] : (j - 6 == i ? 1.0 : 0.0);
    for (int c = 0; c < 6; ++c) {
        int piv = c;
        for (int i = c + 1; i < 6; ++i)
            if (fabs(m[i][c]) > fabs(m[piv][c]))
                piv = i;
        if (m[piv][c] == 0.0)
            return 0;
        for (int j = 0; j < 12; ++j) {
            const double t = m[c][j];
            m[c][j] = m[piv][j];
            m[piv][j] = t;
        }
        const double d = m[c][c];
        for (int j = 0; j < 12; ++j)
            m[c][j] /= d;
        for (int i = 0; i < 6; ++i) {
            if (i == c)
                continue;
            const double f = m[i][c];
            for (int j = 0; j < 12; ++j)
                m[i][j] -= f * m[c][j];
        }
    }
    for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 6; ++j)
            inv[i][j] = m[i][j + 6];
    return 1;
}

/* FK is checked on an accepted pose when the double FK from the home pose comes back to it
 * (another assembly mode would be a right answer to a different question). */
static void fk_reference(const tse_geometry *g, entry *e)
{
    e->fk = 0;
    if (e->r.status != TSE_OK)
        return;
    tse_fk_result f;
    if (tse_fk(g, e->r.q, NULL, &f) != TSE_OK)
        return;
    for (int k = 0; k < 6; ++k)
        if (fabs(f.pose[k] - e->pose[k]) > 1e-9)
            return;
    double J[6][6], inv[6][6];
    if (tse_jacobian(g, e->pose, e->r.q, J) != TSE_OK || !invert6(J, inv))
        return;
    for (int i = 0; i < 6; ++i) {
        double s = 0.0;
        for (int j = 0; j < 6; ++j)
            s += fabs(inv[i][j]);
        e->fk_sens[i] = s;
    }
    e->fk = 1;
}

static int count_status[TSE_STATUS_COUNT];
static int count_scissor[TSE_STATUS_COUNT][4];
static int count_design[2];

static void add(int design, int path_start, const double pose[6], const tse_ik_result *r)
{
    if (ncases >= MAX_CASES) {
        fprintf(stderr, "gen_kin_table: more than %d cases\n", MAX_CASES);
        exit(1);
    }
    entry *e = &cases[ncases++];
    e->design = design;
    e->path_start = path_start;
    e->r = *r;
    memcpy(e->pose, pose, sizeof e->pose);
    fk_reference(&geom[design], e);
    ++count_status[r->status];
    ++count_scissor[r->status][r->scissor];
    ++count_design[design];
}

/* Whether the table still lacks poses of this status failing on this scissor. */
static int needs(tse_status st, int scissor)
{
    if (st == TSE_INVALID || st == TSE_NOCONVERGE)
        return 0; /* invalid: the explicit non-finite poses only */
    if (count_status[st] < QUOTA)
        return 1;
    return st != TSE_OK && count_scissor[st][scissor] < QUOTA_SCISSOR;
}

static int quotas_met(void)
{
    for (int st = TSE_OK; st <= TSE_DEGENERATE; ++st)
        for (int i = st == TSE_OK ? 0 : 1; i <= (st == TSE_OK ? 0 : 3); ++i)
            if (needs((tse_status)st, i))
                return 0;
    return 1;
}

static void round_pose(double p[6])
{
    for (int k = 0; k < 6; ++k)
        p[k] = as_float(p[k]);
}

/* A starting pose from one of four regions: around the workspace, far and wide, low, tilted. */
static void sample_start(double p[6])
{
    const double kind = uniform(0.0, 1.0);
    if (kind < 0.35) {
        p[0] = uniform(-0.35, 0.35), p[1] = uniform(-0.35, 0.35), p[2] = uniform(0.2, 1.7);
        p[3] = uniform(-0.6, 0.6), p[4] = uniform(-0.6, 0.6), p[5] = uniform(-0.9, 0.9);
    } else if (kind < 0.55) {
        p[0] = uniform(-1.2, 1.2), p[1] = uniform(-1.2, 1.2), p[2] = uniform(-0.6, 2.5);
        p[3] = uniform(-1.2, 1.2), p[4] = uniform(-1.2, 1.2), p[5] = uniform(-2.0, 2.0);
    } else if (kind < 0.75) {
        p[0] = uniform(-0.45, 0.45), p[1] = uniform(-0.45, 0.45), p[2] = uniform(-0.15, 0.4);
        p[3] = uniform(-0.8, 0.8), p[4] = uniform(-0.8, 0.8), p[5] = uniform(-0.9, 0.9);
    } else {
        p[0] = uniform(-0.3, 0.3), p[1] = uniform(-0.5, 0.5), p[2] = uniform(0.2, 1.2);
        p[3] = uniform(-1.0, 1.0), p[4] = uniform(-1.0, 1.0), p[5] = uniform(-1.0, 1.0);
    }
    round_pose(p);
}

/* The warm seed the image will use: the newest slides of this path that are all finite. */
static const double *path_seed(int first)
{
    for (int i = ncases - 1; i >= first; --i)
        if (all_finite(cases[i].r.q))
            return cases[i].r.q;
    return NULL;
}

/* A random path: a start whose status still lacks poses, then WALK - 1 small steps. */
static void random_path(void)
{
    const int design = uniform(0.0, 1.0) < 0.3 ? 1 : 0;
    const tse_geometry *g = &geom[design];
    double p[6];
    tse_ik_result r;
    sample_start(p);
    if (!decided(g, p, NULL, &r) || !needs(r.status, r.scissor))
        return;
    const int first = ncases;
    add(design, 1, p, &r);
    for (int n = 1; n < WALK; ++n) {
        for (int attempt = 0; attempt < 50; ++attempt) {
            double s[6];
            for (int k = 0; k < 6; ++k)
                s[k] = p[k] + (k < 3 ? uniform(-0.02, 0.02) : uniform(-0.03, 0.03));
            round_pose(s);
            if (decided(g, s, path_seed(first), &r)) {
                memcpy(p, s, sizeof p);
                add(design, 0, p, &r);
                break;
            }
        }
    }
}

/* The margin a boundary search follows: the smallest type-1 margin (which_nu = 0) or the type-2
 * ratio nu (which_nu = 1) of a pose; -1 where it is not computed (no solution, or for nu a
 * scissor failing first). */
static double margin_of(const tse_geometry *g, const double pose[6], int which_nu)
{
    tse_ik_result r;
    tse_ik(g, pose, NULL, &r);
    if (which_nu)
        return (r.status == TSE_OK || r.status == TSE_DEGENERATE) ? r.nu : -1.0;
    if (r.status == TSE_UNREACHABLE || r.status == TSE_INVALID || r.status == TSE_NOCONVERGE)
        return -1.0;
    double m = 1.0;
    for (int i = 0; i < 3; ++i)
        if (r.mu[i] < m)
            m = r.mu[i];
    return m;
}

/* A path across a thin band at the edge of the workspace, which random poses seldom land in:
 * the singular band (0 < mu < mu_min) in front of the fold where a scissor's solution disappears,
 * well under a millimetre wide; or the degenerate region (nu < nu_min).  From an accepted pose
 * along a random straight line (1 mm / 2 mrad steps) until the status changes; if it changes to
 * singular or unreachable, bisect for a weakest mu inside the band; if to degenerate, for nu
 * inside it; then one more pose 1 mm further.  Path: the start, the pose in the band, the one
 * beyond (when decided), so that warm starts cross the edge too. */
static void boundary_path(void)
{
    const int design = uniform(0.0, 1.0) < 0.3 ? 1 : 0;
    const tse_geometry *g = &geom[design];
    double p[6], d[6];
    tse_ik_result r0, r;
    for (int attempt = 0;; ++attempt) {
        if (attempt == 100)
            return;
        p[0] = uniform(-0.25, 0.25), p[1] = uniform(-0.25, 0.25), p[2] = uniform(0.4, 1.5);
        p[3] = uniform(-0.6, 0.6), p[4] = uniform(-0.6, 0.6), p[5] = uniform(-0.6, 0.6);
        round_pose(p);
        if (decided(g, p, NULL, &r0) && r0.status == TSE_OK)
            break;
    }
    double n = 0.0;
    for (int k = 0; k < 6; ++k) {
        d[k] = uniform(-1.0, 1.0);
        n += d[k] * d[k];
    }
    for (int k = 0; k < 6; ++k)
        d[k] *= (k < 3 ? 1e-3 : 2e-3) / sqrt(n);
    /* x(t) = p + t d; lo: last accepted step, hi: first that is not */
    double lo = 0.0, hi = 0.0, x[6];
    tse_status want;
    for (int step = 1;; ++step) {
        if (step > 800)
            return;
        for (int k = 0; k < 6; ++k)
            x[k] = p[k] + step * d[k];
        tse_ik(g, x, NULL, &r);
        if (r.status == TSE_OK) {
            lo = step;
            continue;
        }
        if (r.status == TSE_SINGULAR || r.status == TSE_UNREACHABLE)
            want = TSE_SINGULAR;
        else if (r.status == TSE_DEGENERATE)
            want = TSE_DEGENERATE;
        else
            return;
        hi = step;
        break;
    }
    const int which_nu = want == TSE_DEGENERATE;
    const double target = which_nu ? uniform(0.2, 0.8) * g->p.nu_min : uniform(0.02, 0.045);
    for (int it = 0; it < 60; ++it) {
        const double mid = 0.5 * (lo + hi);
        for (int k = 0; k < 6; ++k)
            x[k] = p[k] + mid * d[k];
        if (margin_of(g, x, which_nu) > target)
            lo = mid;
        else
            hi = mid;
    }
    double band[6], beyond[6];
    for (int k = 0; k < 6; ++k) {
        band[k] = p[k] + lo * d[k];
        beyond[k] = p[k] + (lo + 1.0) * d[k];
    }
    round_pose(band);
    round_pose(beyond);
    if (!decided(g, band, r0.q, &r) || r.status != want || !needs(want, r.scissor))
        return;
    add(design, 1, p, &r0);
    add(design, 0, band, &r);
    const double seed[6] = {r.q[0], r.q[1], r.q[2], r.q[3], r.q[4], r.q[5]};
    if (decided(g, beyond, all_finite(seed) ? seed : r0.q, &r))
        add(design, 0, beyond, &r);
}

/* A smooth path through the workspace, 2 to 4 mm a pose: what warm starts see in motion. */
static void smooth_path(int design, double phase, int n)
{
    const tse_geometry *g = &geom[design];
    const int first = ncases;
    for (int i = 0; i < n; ++i) {
        const double t = phase + 0.02 * i;
        double p[6] = {0.08 * sin(t), 0.06 * sin(2.0 * t), 1.05 + 0.15 * sin(3.0 * t),
                       0.05 * sin(t + 0.3), 0.05 * cos(2.0 * t), 0.1 * sin(t)};
        round_pose(p);
        tse_ik_result r;
        if (decided(g, p, path_seed(first), &r))
            add(design, i == 0 || ncases == first, p, &r);
    }
}

static void invalid_path(void)
{
    const tse_geometry *g = &geom[0];
    const int first = ncases;
    for (int k = 0; k < 8; ++k) {
        double p[6] = {0.01, -0.02, 1.0, 0.02, 0.01, -0.03};
        if (k < 6)
            p[k] = NAN;
        else
            p[k - 6 + 2] = k == 6 ? INFINITY : -INFINITY;
        tse_ik_result r;
        tse_ik(g, p, path_seed(first), &r);
        if (r.status != TSE_INVALID || r.scissor != 1) {
            fprintf(stderr, "gen_kin_table: a non-finite pose is not invalid\n");
            exit(1);
        }
        add(0, k == 0, p, &r);
        /* a good pose between the bad ones: the warm seed must survive them */
        const double good[6] = {as_float(0.01 * k), -0.02, 1.0, 0.02, 0.01, -0.03};
        if (decided(g, good, path_seed(first), &r))
            add(0, 0, good, &r);
    }
}

/* Reference poses, in um and urad (the CAN protocol's units): a start near the home height, a
 * near and a far move, a pure turn, and the two targets of the controller image's script. */
static const struct {
    const char *name;
    int32_t u[6];
} refs[] = {
    {"start", {0, 0, 1100000, 0, 0, 0}},
    {"near", {30000, -20000, 1050000, 30000, -20000, 50000}},
    {"far", {-100000, 80000, 850000, -100000, 80000, -150000}},
    {"turn", {0, 0, 1100000, 0, 0, 450000}},
    {"ctl_a", {10000, -8000, 1100000, 10000, -5000, 15000}},
    {"ctl_b", {-30000, 20000, 1080000, -20000, 20000, -40000}},
};
#define NREFS (int)(sizeof refs / sizeof refs[0])
static tse_ik_result ref_ik[NREFS];

static void make_refs(void)
{
    for (int i = 0; i < NREFS; ++i) {
        double p[6];
        for (int k = 0; k < 6; ++k)
            p[k] = refs[i].u[k] * 1e-6;
        tse_ik_result *r = &ref_ik[i];
        if (!decided(&geom[0], p, NULL, r) || r->status != TSE_OK || !(r->mu[0] >= 0.1 && r->mu[1] >= 0.1 && r->mu[2] >= 0.1)) {
            fprintf(stderr, "gen_kin_table: reference pose %s is not accepted with margin\n", refs[i].name);
            exit(1);
        }
    }
}

#define PATH_SAMPLES 40
typedef struct {
    double from[6], to[6], u_first;
    tse_status status;
    int scissor;
} path_entry;
#define KIN_PATHS_MAX 2
static path_entry paths[KIN_PATHS_MAX];
static int npaths;

static void path_pose(const path_entry *e, double u, double p[6])
{
    for (int k = 0; k < 6; ++k)
        p[k] = k < 3 ? e->from[k] + u * (e->to[k] - e->from[k]) : e->from[k];
}

/* Straight paths at a fixed orientation between two accepted poses, through a region where the
 * inverse kinematics fails: the first u where it fails, bisected, and the same status on the same
 * scissor for a while after it, so that the planner's first failing segment must name them.  The
 * workspace at a fixed orientation is nearly convex when the plate is level; with a strongly
 * tilted plate, straight paths cross the degenerate surfaces (nu < nu_min) and the angle stops
 * between accepted poses.  One path per status. */
static void make_paths(void)
{
    for (long attempt = 0; attempt < 100000 && npaths < KIN_PATHS_MAX; ++attempt) {
        path_entry e;
        const double o[3] = {uniform(-0.8, 0.8), uniform(-0.8, 0.8), uniform(-0.8, 0.8)};
        for (int k = 0; k < 3; ++k)
            e.from[3 + k] = e.to[3 + k] = o[k];
        e.from[0] = uniform(-0.3, 0.3), e.from[1] = uniform(-0.4, 0.4), e.from[2] = uniform(0.3, 1.3);
        e.to[0] = uniform(-0.3, 0.3), e.to[1] = uniform(-0.4, 0.4), e.to[2] = uniform(0.3, 1.3);
        round_pose(e.from);
        round_pose(e.to);
        double len = 0.0;
        for (int k = 0; k < 3; ++k)
            len += (e.to[k] - e.from[k]) * (e.to[k] - e.from[k]);
        len = sqrt(len);
        if (len < 0.1 || len > 0.6)
            continue;
        tse_ik_result a, b, r;
        if (!decided(&geom[0], e.from, NULL, &a) || a.status != TSE_OK || !decided(&geom[0], e.to, NULL, &b) ||
            b.status != TSE_OK)
            continue;
        /* scan, warm like the planner, then bisect between the last accepted and first failing u */
        double lo = 0.0, hi = -1.0, seed[6], p[6];
        memcpy(seed, a.q, sizeof seed);
        for (int s = 1; s <= 2000; ++s) {
            const double u = s / 2000.0;
            path_pose(&e, u, p);
            tse_ik(&geom[0], p, seed, &r);
            if (r.status != TSE_OK) {
                hi = u;
                break;
            }
            lo = u;
            memcpy(seed, r.q, sizeof seed);
        }
        if (hi < 0.0 || lo < 0.1 || hi > 0.9)
            continue;
        for (int it = 0; it < 60; ++it) {
            const double mid = 0.5 * (lo + hi);
            path_pose(&e, mid, p);
            tse_ik(&geom[0], p, NULL, &r);
            if (r.status == TSE_OK)
                lo = mid;
            else
                hi = mid;
        }
        e.u_first = hi;
        path_pose(&e, hi, p);
        tse_ik(&geom[0], p, NULL, &r);
        e.status = r.status;
        e.scissor = r.scissor;
        int same = r.status != TSE_NOCONVERGE;
        for (int s = 1; s <= PATH_SAMPLES && same; ++s) {
            path_pose(&e, hi + KIN_PATH_AFTER * s / PATH_SAMPLES, p);
            tse_ik(&geom[0], p, NULL, &r);
            same = r.status == e.status && r.scissor == e.scissor;
        }
        /* accepted up to 1e-4 before it (the scan saw every 5e-4 accepted, warm) */
        path_pose(&e, e.u_first - 1e-4, p);
        tse_ik(&geom[0], p, NULL, &r);
        if (!same || r.status != TSE_OK)
            continue;
        int dup = 0;
        for (int i = 0; i < npaths; ++i)
            dup |= paths[i].status == e.status;
        if (!dup)
            paths[npaths++] = e;
    }
    if (npaths < 2) {
        fprintf(stderr, "gen_kin_table: only %d failing paths found\n", npaths);
        exit(1);
    }
}

static void print_real(FILE *f, double x, int is_float)
{
    if (isnan(x))
        fputs("NAN", f);
    else if (isinf(x))
        fputs(x > 0 ? "INFINITY" : "-INFINITY", f);
    else if (is_float)
        fprintf(f, "%.8ef", (double)(float)x); /* 9 digits: exact for a float */
    else
        fprintf(f, "%.16e", x);
}

static void write_table(FILE *f)
{
    fputs("/* Generated by tests/target/gen_kin_table.c (double precision, on the host): do not "
          "edit. */\n#include <math.h>\n\n#include \"kin_table.h\"\n\n",
          f);
    fputs("const kin_design kin_designs[KIN_DESIGNS] = {\n", f);
    for (int d = 0; d < 2; ++d) {
        fputs("    {", f);
        for (int k = 0; k < 11; ++k) {
            print_real(f, design_f[d][k], 1);
            fputs(k < 10 ? ", " : "},\n", f);
        }
    }
    fputs("};\n\nconst kin_case kin_cases[] = {\n", f);
    for (int i = 0; i < ncases; ++i) {
        const entry *e = &cases[i];
        fprintf(f, "    {%d, %d, %d, %d, %d, {", e->design, e->path_start, (int)e->r.status, e->r.scissor, e->fk);
        for (int k = 0; k < 6; ++k) {
            print_real(f, e->pose[k], 1);
            fputs(k < 5 ? ", " : "}, {", f);
        }
        for (int k = 0; k < 6; ++k) {
            print_real(f, e->r.q[k], 0);
            fputs(k < 5 ? ", " : "}, {", f);
        }
        for (int k = 0; k < 3; ++k) {
            print_real(f, e->r.mu[k], 1);
            fputs(k < 2 ? ", " : "}, {", f);
        }
        for (int k = 0; k < 6; ++k) {
            print_real(f, e->fk ? e->fk_sens[k] : 0.0, 1);
            fputs(k < 5 ? ", " : "}},\n", f);
        }
    }
    fprintf(f, "};\n\nconst unsigned kin_case_count = %d;\n", ncases);
    fputs("\nconst kin_ref kin_refs[KIN_REFS] = {\n", f);
    for (int i = 0; i < NREFS; ++i) {
        fprintf(f, "    {\"%s\", {", refs[i].name);
        for (int k = 0; k < 6; ++k)
            fprintf(f, "%ld%s", (long)refs[i].u[k], k < 5 ? ", " : "}, {");
        for (int k = 0; k < 6; ++k) {
            print_real(f, ref_ik[i].q[k], 0);
            fputs(k < 5 ? ", " : "}},\n", f);
        }
    }
    fputs("};\n\nconst kin_path kin_paths[] = {\n", f);
    for (int i = 0; i < npaths; ++i) {
        fputs("    {{", f);
        for (int k = 0; k < 6; ++k) {
            print_real(f, paths[i].from[k], 1);
            fputs(k < 5 ? ", " : "}, {", f);
        }
        for (int k = 0; k < 6; ++k) {
            print_real(f, paths[i].to[k], 1);
            fputs(k < 5 ? ", " : "}, ", f);
        }
        print_real(f, paths[i].u_first, 0);
        fprintf(f, ", %d, %d},\n", (int)paths[i].status, paths[i].scissor);
    }
    fprintf(f, "};\n\nconst unsigned kin_path_count = %d;\n", npaths);
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: gen_kin_table OUTPUT.c\n");
        return 2;
    }
    make_designs();
    invalid_path();
    smooth_path(0, 0.0, 30);
    smooth_path(0, 2.0, 30);
    smooth_path(1, 4.0, 30);
    long tries = 0;
    while (!quotas_met()) {
        if (++tries > 2000000) {
            fprintf(stderr, "gen_kin_table: quotas not met after %ld paths\n", tries);
            for (int st = 0; st < TSE_STATUS_COUNT; ++st)
                fprintf(stderr, "  %-12s %d (%d %d %d)\n", tse_status_name((tse_status)st), count_status[st],
                        count_scissor[st][1], count_scissor[st][2], count_scissor[st][3]);
            return 1;
        }
        if (tries % 4 == 0)
            boundary_path();
        else
            random_path();
    }
    make_refs();
    make_paths();
    FILE *f = fopen(argv[1], "w");
    if (!f) {
        perror(argv[1]);
        return 1;
    }
    write_table(f);
    if (fclose(f) != 0) {
        perror(argv[1]);
        return 1;
    }
    int nfk = 0;
    for (int i = 0; i < ncases; ++i)
        nfk += cases[i].fk;
    printf("gen_kin_table: %d poses (design 0: %d, design 1: %d), %d with FK, from %ld random paths\n", ncases,
           count_design[0], count_design[1], nfk, tries);
    for (int st = 0; st < TSE_STATUS_COUNT; ++st)
        printf("  %-12s %3d  (scissor 1/2/3: %d %d %d)\n", tse_status_name((tse_status)st), count_status[st],
               count_scissor[st][1], count_scissor[st][2], count_scissor[st][3]);
    for (int i = 0; i < npaths; ++i)
        printf("  path %d: %s on scissor %d from u = %.6f\n", i, tse_status_name(paths[i].status), paths[i].scissor,
               paths[i].u_first);
    return 0;
}
