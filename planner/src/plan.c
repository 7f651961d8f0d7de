/* plan_make: the input checked, the memory laid out, the path and its kinematics, then the time law
 * held to the waypoints' times and run through the validator until it accepts (plan.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fw/reject.h"
#include "fw/traj_stop.h"
#include "plan_internal.h"

void plan_options_default(plan_options *o)
{
    o->period = PLAN_PERIOD_DEFAULT;
    o->blend = 0.0;
    o->retries = PLAN_RETRIES_DEFAULT;
    /* The rows' rounding to whole micrometres moves a slide's speed by under 0.1 % at 20 ms, and
     * its acceleration, as the validator measures it over 10 ms strides, by up to a few per cent
     * where rows are 10 ms apart; the retries take what the margins leave. */
    o->v_margin = 0.995;
    o->a_margin = 0.985;
    o->jmax = 0.0; /* none: the controller bounds no trajectory's jerk */
    o->rates = FW_RATES_BUILT_IN;
}

static int bad(plan_result *r, int waypoint, const char *why)
{
    r->status = PLAN_BAD_INPUT;
    r->waypoint = waypoint;
    r->why = why;
    return -1;
}

static int check_input(const plan_waypoint *wp, int n, const plan_options *o, plan_result *r)
{
    if (!(o->period >= PLAN_PERIOD_MIN && o->period <= PLAN_PERIOD_MAX))
        return bad(r, -1, "the period must be 0.001 s to 1 s");
    if (!(o->blend >= 0.0 && o->blend <= PLAN_BLEND_MAX))
        return bad(r, -1, "the blend tolerance must be 0 to 1 m");
    if (!(o->v_margin > 0.0 && o->v_margin <= 1.0 && o->a_margin > 0.0 && o->a_margin <= 1.0) || o->retries < 0)
        return bad(r, -1, "the margins must be within (0, 1] and the retries at least 0");
    if (!(o->jmax == PLAN_JMAX_CONTROLLER || (o->jmax >= 0.0 && o->jmax <= PLAN_JERK_MAX)))
        return bad(r, -1, "the jerk limit must be 0 (none), a positive number of m/s^3 up to 1e6, or the controller's");
    if (n < 2)
        return bad(r, -1, "a path needs at least 2 waypoints");
    if (n > PLAN_WAYPOINTS_MAX)
        return bad(r, -1, "more than 100000 waypoints");
    double t_prev = 0.0;
    for (int i = 0; i < n; ++i) {
        for (int k = 0; k < 6; ++k)
            if (!isfinite(wp[i].pose[k]))
                return bad(r, i, "a pose coordinate is not a finite number");
        if (!isnan(wp[i].v) && !(wp[i].v > 0.0 && isfinite(wp[i].v)))
            return bad(r, i, "its speed cap v must be a positive number of m/s");
        if (isnan(wp[i].t))
            continue;
        if (i == 0 && wp[i].t != 0.0)
            return bad(r, i, "the first waypoint is where the path starts: its t must be 0 (or empty)");
        if (i > 0 && !(wp[i].t > t_prev && isfinite(wp[i].t)))
            return bad(r, i, "its t must come after the previous waypoint's given t");
        t_prev = wp[i].t;
    }
    return 0;
}

/* The layout of a plan in memory: its arrays one after another, each 8-byte aligned. */
typedef struct {
    size_t total;
    size_t ws, val, m2, pieces, tw, pace, qs, qss, qsj, vcap2, slow, stretch, K, x, t, xs, ts, cap;
} layout;

static size_t take(size_t *at, size_t bytes)
{
    const size_t here = *at;
    *at += (bytes + 7u) & ~(size_t)7u;
    return here;
}

static void lay_out(int n, long N, layout *l)
{
    size_t at = 0;
    take(&at, sizeof(plan));
    const size_t nn = (size_t)n, g = (size_t)N + 1u;
    l->ws = take(&at, nn * sizeof(double));
    l->val = take(&at, nn * 6 * sizeof(double));
    l->m2 = take(&at, nn * 6 * sizeof(double));
    l->pieces = take(&at, 2 * nn * sizeof(plan_piece));
    l->tw = take(&at, nn * sizeof(int64_t));
    l->pace = take(&at, nn * sizeof(double));
    l->qs = take(&at, g * 6 * sizeof(double));
    l->qss = take(&at, g * 6 * sizeof(double));
    l->qsj = take(&at, g * 6 * sizeof(double));
    l->vcap2 = take(&at, g * sizeof(double));
    l->slow = take(&at, g * sizeof(double));
    l->stretch = take(&at, g * sizeof(int));
    l->K = take(&at, g * sizeof(double));
    l->x = take(&at, g * sizeof(double));
    l->t = take(&at, g * sizeof(double));
    l->xs = take(&at, g * sizeof(double));
    l->ts = take(&at, g * sizeof(double));
    l->cap = take(&at, g * sizeof(double));
    l->total = at;
}

/* The grid points a path of chord length `len` gets (an upper bound for its blended form). */
static long grid_points(double len)
{
    const double n = ceil(len / PLAN_GRID_STEP);
    return n < PLAN_GRID_MIN ? PLAN_GRID_MIN : n > (double)PLAN_GRID_MAX ? PLAN_GRID_MAX + 1 : (long)n;
}

/* The chord length of the waypoints in the path's metric, as plan_path_build measures it. */
static double chord_length(const plan_waypoint *wp, int n, double r_top)
{
    double len = 0.0;
    for (int i = 1; i < n; ++i) {
        double d2 = 0.0;
        for (int k = 0; k < 6; ++k) {
            double d = wp[i].pose[k] - wp[i - 1].pose[k];
            if (k >= 3)
                d = r_top * remainder(d, 2.0 * PLAN_PI);
            d2 += d * d;
        }
        len += sqrt(d2);
    }
    return len;
}

double plan_row_spacing_min(const fw_param_set *s, fw_rates r)
{
    tse_geometry g;
    fw_limits lim;
    if (traj_limits(s, r, &g, &lim) != 0)
        return PLAN_ROW_MIN_US * 1e-6;
    const double need = (double)fw_traj_stop_reach(fw_traj_stop_time(lim.slide_vmax, lim.slide_amax, 0.0)) +
                         2.0 / (double)lim.segment_hz + PLAN_QUEUE_MARGIN_S;
    return fmax(ceil(need / PLAN_QUEUED_ROWS * 1e6) * 1e-6, PLAN_ROW_MIN_US * 1e-6);
}

size_t plan_bytes(const fw_param_set *s, const plan_waypoint *wp, int n, const plan_options *o)
{
    plan_result r;
    tse_geometry g;
    fw_limits lim;
    if (check_input(wp, n, o, &r) != 0 || traj_limits(s, o->rates, &g, &lim) != 0)
        return 0;
    const long N = grid_points(chord_length(wp, n, g.r_top));
    if (N > PLAN_GRID_MAX)
        return 0;
    layout l;
    lay_out(n, N, &l);
    return l.total;
}

/* Slows the stretch of the path around refused row r->row: the rows from the one before it back
 * over the validator's acceleration window, to the one after, and a jerk window more on each side
 * (the smoothed law's speed at a point is the average of the law's around it: plan_jerk_smooth). */
static void slow_down(plan *p, const plan_result *r)
{
    plan_cursor c;
    plan_row row;
    double t_prev = 0.0, t_row = 0.0;
    long k = 0;
    for (plan_rows_begin(p, &c); plan_rows_next(p, &c, &row); ++k) {
        if (k == r->row) {
            t_row = row.t - (double)p->hold_us * 1e-6;
            break;
        }
        t_prev = row.t - (double)p->hold_us * 1e-6;
    }
    const double stride = (double)FW_ACC_STRIDE / (double)p->lim.segment_hz;
    const double from = t_prev - 2.0 * stride - p->opt.period - p->tj, to = t_row + stride + p->tj;
    const double ratio = fmax((double)r->reject[6] * 1e-3, 1.0);
    const bool accel = r->reject[5] >= FW_REJECT_LIMIT;
    const double f = fmin(0.97, accel ? sqrt(0.995 / ratio) : 0.995 / ratio);
    plan_grid *gr = &p->grid;
    for (long i = 0; i <= gr->N; ++i)
        if (gr->t[i] >= from && gr->t[i] <= to)
            gr->slow[i] *= f;
}

/* Plans the time law with each stretch ending at a waypoint with a given time held to the share of
 * the limits that passes it then: a bisection on that share, stretch by stretch, three sweeps (a
 * slower stretch may make the one before it brake earlier).  Returns 0, or -1 with r (TIME). */
static int keep_times(plan *p, plan_result *r)
{
    bool any = false;
    for (int w = 1; w < p->n; ++w)
        any = any || !isnan(p->wp[w].t);
    if (!any)
        return plan_time_law(p, r);
    for (int sweep = 0; sweep < 3; ++sweep) {
        int from = 0;
        for (int w = 1; w < p->n; ++w) {
            if (isnan(p->wp[w].t))
                continue;
            const int64_t want = llround(p->wp[w].t * 1e6) - p->hold_us;
            double hi = 1.0, lo = 1.0;
            for (int i = from; i < w; ++i)
                p->pace[i] = 1.0;
            if (plan_time_law(p, r) != 0)
                return -1;
            if (p->tw_us[w] > want + PLAN_ROW_MIN_US / 2) {
                r->status = PLAN_TIME;
                r->waypoint = w;
                r->t_needed = (double)(p->tw_us[w] + p->hold_us) * 1e-6;
                return -1;
            }
            /* Slower until it is late, then bisect between on time and late. */
            while (p->tw_us[w] < want && lo > 1e-4) {
                hi = lo;
                lo *= 0.5;
                for (int i = from; i < w; ++i)
                    p->pace[i] = lo;
                if (plan_time_law(p, r) != 0)
                    return -1;
            }
            for (int it = 0; it < 50 && llabs(p->tw_us[w] - want) > 100; ++it) {
                const double mid = 0.5 * (lo + hi);
                for (int i = from; i < w; ++i)
                    p->pace[i] = mid;
                if (plan_time_law(p, r) != 0)
                    return -1;
                if (p->tw_us[w] < want)
                    hi = mid;
                else
                    lo = mid;
            }
            from = w;
        }
    }
    for (int w = 1; w < p->n; ++w) {
        if (!isnan(p->wp[w].t) && llabs(p->tw_us[w] + p->hold_us - llround(p->wp[w].t * 1e6)) > PLAN_ROW_MIN_US) {
            r->status = PLAN_TIME;
            r->waypoint = w;
            r->t_needed = NAN; /* each can be kept, not all together */
            return -1;
        }
    }
    return 0;
}

plan *plan_make(void *mem, size_t bytes, const fw_param_set *s, const plan_waypoint *wp, int n,
                const plan_options *o, plan_result *r)
{
    memset(r, 0, sizeof *r);
    r->waypoint = -1;
    r->row = -1;
    if (check_input(wp, n, o, r) != 0)
        return NULL;
    tse_geometry g;
    fw_limits lim;
    if (traj_limits(s, o->rates, &g, &lim) != 0) {
        r->status = PLAN_PARAMS;
        return NULL;
    }
    const long N = grid_points(chord_length(wp, n, g.r_top));
    layout l;
    lay_out(n, N > PLAN_GRID_MAX ? 0 : N, &l);
    if (N > PLAN_GRID_MAX || !mem || bytes < l.total) {
        r->status = PLAN_TOO_LONG;
        return NULL;
    }
    char *base = mem;
    plan *p = mem;
    memset(p, 0, sizeof *p);
    p->wp = wp;
    p->n = n;
    p->opt = *o;
    p->g = g;
    p->lim = lim;
    p->set = *s;
    const double stride = (double)FW_ACC_STRIDE / (double)lim.segment_hz;
    p->vlim = (double)lim.slide_vmax * o->v_margin;
    p->row_f = fmin(1.0, stride / o->period);
    p->alim = (double)(FW_PATH_MARGIN * lim.slide_amax) * o->a_margin * p->row_f; /* what rows may use */
    p->jmax = o->jmax == PLAN_JMAX_CONTROLLER ? (double)fw_slide_jmax(&lim) : o->jmax;
    p->period_us = llround(o->period * 1e6);
    p->hold_us = s->v[FP_TRAJ_LEAD] > PLAN_ROW_MIN_US ? s->v[FP_TRAJ_LEAD] : PLAN_ROW_MIN_US;
    p->min_us = llround(plan_row_spacing_min(s, o->rates) * 1e6);
    if (p->period_us < p->min_us) {
        r->status = PLAN_BAD_INPUT;
        r->why = "the period is shorter than the controller's queue allows at its speed limit (plan_row_spacing_min)";
        r->period_min = (double)p->min_us * 1e-6;
        return NULL;
    }
    p->path.r_top = g.r_top;
    p->path.ws = (double *)(base + l.ws);
    p->path.val = (double (*)[6])(base + l.val);
    p->path.m2 = (double (*)[6])(base + l.m2);
    p->path.pieces = (plan_piece *)(base + l.pieces);
    p->tw_us = (int64_t *)(base + l.tw);
    p->pace = (double *)(base + l.pace);
    plan_grid *gr = &p->grid;
    gr->qs = (double (*)[6])(base + l.qs);
    gr->qss = (double (*)[6])(base + l.qss);
    gr->qsj = (double (*)[6])(base + l.qsj);
    gr->vcap2 = (double *)(base + l.vcap2);
    gr->slow = (double *)(base + l.slow);
    gr->stretch = (int *)(base + l.stretch);
    gr->K = (double *)(base + l.K);
    gr->x = (double *)(base + l.x);
    gr->t = (double *)(base + l.t);
    gr->xs = (double *)(base + l.xs);
    gr->ts = (double *)(base + l.ts);
    gr->cap = (double *)(base + l.cap);
    if (plan_path_build(&p->path, wp, n, o->blend, r) != 0)
        return NULL;
    /* The blended path is no longer than the chords: its grid is at most the one laid out. */
    gr->N = grid_points(p->path.length);
    gr->h = p->path.length / (double)gr->N;
    for (long i = 0; i <= gr->N; ++i)
        gr->slow[i] = 1.0;
    for (int i = 0; i < n; ++i)
        p->pace[i] = 1.0;
    if (plan_grid_solve(p, r) != 0)
        return NULL;
    for (;;) {
        if (keep_times(p, r) != 0)
            return NULL;
        const int v = plan_validate(p, r);
        if (v == 0) {
            p->retries = r->retries;
            return p;
        }
        if (r->status != PLAN_REFUSED || r->reject[2] != FW_REASON_TIMING || r->retries >= o->retries)
            return NULL;
        slow_down(p, r);
        ++r->retries;
        const int retries = r->retries;
        memset(r, 0, sizeof *r);
        r->waypoint = -1;
        r->row = -1;
        r->retries = retries;
    }
}
