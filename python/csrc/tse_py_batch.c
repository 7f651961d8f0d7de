#define _POSIX_C_SOURCE 200809L /* pthread_sigmask */
/* The batch entry points of libtse_kin.so, compiled once per precision: see tse_py.h. */
#define TSE_PY_BATCH
#include "tse_py.h"

#include <pthread.h>
#include <signal.h>
#include <stdatomic.h>
#include <string.h>

#include "tse/fk.h"
#include "tse/ik.h"
#include "tse/jacobian.h"
#include "tse/metrics.h"

static void to_real(const double *in, tse_real *out, int n)
{
    for (int k = 0; k < n; ++k)
        out[k] = (tse_real)in[k];
}

static void to_double(const tse_real *in, double *out, int n)
{
    for (int k = 0; k < n; ++k)
        out[k] = (double)in[k];
}

static void params_of(const double v[TSE_PY_NPARAMS], tse_params *t)
{
    t->L = (tse_real)v[TSE_PARAM_L - 1];
    t->k1 = (tse_real)v[TSE_PARAM_K1 - 1];
    t->eta = (tse_real)v[TSE_PARAM_ETA - 1];
    t->k3 = (tse_real)v[TSE_PARAM_K3 - 1];
    t->k4 = (tse_real)v[TSE_PARAM_K4 - 1];
    t->alpha_min = (tse_real)v[TSE_PARAM_ALPHA_MIN - 1];
    t->alpha_max = (tse_real)v[TSE_PARAM_ALPHA_MAX - 1];
    t->s_min = (tse_real)v[TSE_PARAM_S_MIN - 1];
    t->s_max = (tse_real)v[TSE_PARAM_S_MAX - 1];
    t->mu_min = (tse_real)v[TSE_PARAM_MU_MIN - 1];
    t->nu_min = (tse_real)v[TSE_PARAM_NU_MIN - 1];
}

/* The geometry of the set rounded to this precision; TSE_PARAM_OK or the first rejected one. */
static int geometry_of(const double v[TSE_PY_NPARAMS], tse_geometry *g)
{
    tse_params t;
    params_of(v, &t);
    return (int)tse_geometry_init(g, &t);
}

int tse_py_check(const double v[TSE_PY_NPARAMS])
{
    tse_params t;
    params_of(v, &t);
    return (int)tse_params_check(&t);
}

/* The seed of row i: the last ok answer when warm and there is one, else the caller's. */
static const tse_real *seed_of(long i, const double *seed, long stride, int have_last, const tse_real *last,
                               tse_real buf[6])
{
    if (have_last)
        return last;
    if (!seed)
        return NULL;
    to_real(seed + i * stride, buf, 6);
    return buf;
}

/* One ik or fk call: its arrays, shared read-only by the threads, each writing its own rows. */
typedef struct {
    const tse_geometry *g;
    const double *in, *seed;
    long seed_stride;
    int warm;
    int *status, *scissor;
    double *out;
} batch;

typedef void (*rows_fn)(const batch *b, long begin, long end);

/* Rows [begin, end) of an ik call.  Warm, the rows run from 0 in one piece (see run_rows). */
static void ik_rows(const batch *b, long begin, long end)
{
    tse_real last[6], buf[6], p[6];
    int have_last = 0;
    for (long i = begin; i < end; ++i) {
        to_real(b->in + 6 * i, p, 6);
        tse_ik_result r;
        const tse_status st = tse_ik(b->g, p, seed_of(i, b->seed, b->seed_stride, have_last, last, buf), &r);
        b->status[i] = (int)st;
        b->scissor[i] = st == TSE_OK ? 0 : r.scissor;
        to_double(r.q, b->out + 6 * i, 6);
        if (b->warm && st == TSE_OK) {
            memcpy(last, r.q, sizeof last);
            have_last = 1;
        }
    }
}

static void fk_rows(const batch *b, long begin, long end)
{
    tse_real last[6], buf[6], qq[6];
    int have_last = 0;
    for (long i = begin; i < end; ++i) {
        to_real(b->in + 6 * i, qq, 6);
        tse_fk_result r;
        const tse_status st = tse_fk(b->g, qq, seed_of(i, b->seed, b->seed_stride, have_last, last, buf), &r);
        b->status[i] = (int)st;
        b->scissor[i] = st == TSE_OK ? 0 : r.scissor;
        for (int k = 0; k < 6; ++k)
            b->out[6 * i + k] = st == TSE_OK ? (double)r.pose[k] : (double)NAN;
        if (b->warm && st == TSE_OK) {
            memcpy(last, r.pose, sizeof last);
            have_last = 1;
        }
    }
}

/* Threads.  A cold batch's rows are independent (a row's answer depends on its pose and seed
 * only), so they are shared out in contiguous blocks of TSE_PY_BLOCK rows, each thread (the
 * calling thread one of them) taking the next block nobody has taken until none is left: rows
 * differ in cost (an unreachable pose costs several reachable ones, and a grid puts them
 * together) and a thread may get less of a busy machine than another, so fixed shares would
 * leave threads idle while one still works.  Each row is computed by the same code from the same
 * inputs as on one thread, so the answers do not depend on the thread count or on who took which
 * block.  A warm batch seeds each row with the last ok row before it: it runs in one piece on the
 * calling thread, as does a batch of fewer than TSE_PY_PARALLEL_MIN rows.  Thread stacks and
 * handles are all that is taken, and released before returning; a thread that cannot be started
 * is simply not there to take blocks. */
enum { TSE_PY_BLOCK = 1024, TSE_PY_PARALLEL_MIN = 4096, TSE_PY_MAX_THREADS = 64 };

typedef struct {
    rows_fn fn;
    const batch *b;
    long n;
    atomic_long next; /* the first row of the next block nobody has taken */
} shared_rows;

static void *take_blocks(void *arg)
{
    shared_rows *w = arg;
    for (;;) {
        const long begin = atomic_fetch_add(&w->next, TSE_PY_BLOCK);
        if (begin >= w->n)
            return NULL;
        w->fn(w->b, begin, begin + TSE_PY_BLOCK < w->n ? begin + TSE_PY_BLOCK : w->n);
    }
}

static void run_rows(rows_fn fn, const batch *b, long n, int threads)
{
    long t = threads < TSE_PY_MAX_THREADS ? threads : TSE_PY_MAX_THREADS;
    if (b->warm || n < TSE_PY_PARALLEL_MIN || t <= 1) {
        fn(b, 0, n);
        return;
    }
    const long blocks = (n + TSE_PY_BLOCK - 1) / TSE_PY_BLOCK;
    if (t > blocks)
        t = blocks;
    shared_rows w = {.fn = fn, .b = b, .n = n};
    atomic_init(&w.next, 0);
    pthread_t tid[TSE_PY_MAX_THREADS];
    long started = 0;
    /* The workers take no signals: they stay with the interpreter's threads. */
    sigset_t all, old;
    sigfillset(&all);
    const int masked = pthread_sigmask(SIG_SETMASK, &all, &old) == 0;
    while (started < t - 1 && pthread_create(&tid[started], NULL, take_blocks, &w) == 0)
        ++started;
    if (masked)
        pthread_sigmask(SIG_SETMASK, &old, NULL);
    take_blocks(&w);
    for (long k = 0; k < started; ++k)
        pthread_join(tid[k], NULL);
}

int tse_py_ik(const double v[TSE_PY_NPARAMS], long n, const double *poses, const double *seed, long seed_stride,
              int warm, int threads, int *status, int *scissor, double *q)
{
    tse_geometry g;
    const int bad = geometry_of(v, &g);
    if (bad != TSE_PARAM_OK)
        return bad;
    const batch b = {&g, poses, seed, seed_stride, warm, status, scissor, q};
    run_rows(ik_rows, &b, n, threads);
    return TSE_PARAM_OK;
}

int tse_py_fk(const double v[TSE_PY_NPARAMS], long n, const double *q, const double *seed, long seed_stride,
              int warm, int threads, int *status, int *scissor, double *pose)
{
    tse_geometry g;
    const int bad = geometry_of(v, &g);
    if (bad != TSE_PARAM_OK)
        return bad;
    const batch b = {&g, q, seed, seed_stride, warm, status, scissor, pose};
    run_rows(fk_rows, &b, n, threads);
    return TSE_PARAM_OK;
}

int tse_py_jacobian(const double v[TSE_PY_NPARAMS], long n, const double *poses, int *status, int *scissor,
                    double *J, double *sv)
{
    tse_geometry g;
    const int bad = geometry_of(v, &g);
    if (bad != TSE_PARAM_OK)
        return bad;
    for (long i = 0; i < n; ++i) {
        double *Ji = J + 36 * i, *svi = sv + 6 * i;
        for (int k = 0; k < 36; ++k)
            Ji[k] = (double)NAN;
        for (int k = 0; k < 6; ++k)
            svi[k] = (double)NAN;
        tse_real p[6];
        to_real(poses + 6 * i, p, 6);
        tse_ik_result r;
        tse_status st = tse_ik(&g, p, NULL, &r);
        scissor[i] = st == TSE_OK ? 0 : r.scissor;
        tse_real Jr[6][6], s[6];
        if (st == TSE_OK)
            st = tse_jacobian(&g, p, r.q, Jr);
        status[i] = (int)st;
        if (st != TSE_OK)
            continue;
        for (int k = 0; k < 6; ++k)
            to_double(Jr[k], Ji + 6 * k, 6);
        tse_singular_values(Jr, s);
        /* dp/dq is the inverse of dq/dp: its singular values are the reciprocals, order reversed. */
        for (int k = 0; k < 6; ++k)
            svi[k] = 1.0 / (double)s[5 - k];
    }
    return TSE_PARAM_OK;
}

int tse_py_haf(const double v[TSE_PY_NPARAMS], long n, const double *z, int *status, double *haf)
{
    tse_geometry g;
    const int bad = geometry_of(v, &g);
    if (bad != TSE_PARAM_OK)
        return bad;
    for (long i = 0; i < n; ++i) {
        tse_real h = (tse_real)NAN;
        const tse_status st = tse_haf(&g.p, (tse_real)z[i], &h);
        status[i] = (int)st;
        haf[i] = st == TSE_OK ? (double)h : (double)NAN;
    }
    return TSE_PARAM_OK;
}

int tse_py_sigma_z(const double v[TSE_PY_NPARAMS], long n, const double *z, int *status, double *sigma)
{
    tse_geometry g;
    const int bad = geometry_of(v, &g);
    if (bad != TSE_PARAM_OK)
        return bad;
    for (long i = 0; i < n; ++i) {
        tse_real s = (tse_real)NAN;
        const tse_status st = tse_sigma_z(&g, (tse_real)z[i], &s);
        status[i] = (int)st;
        sigma[i] = st == TSE_OK ? (double)s : (double)NAN;
    }
    return TSE_PARAM_OK;
}

int tse_py_workspace(const double v[TSE_PY_NPARAMS], int n_r, int n_phi, int n_z, const double orientation[3],
                     int *status, long *reachable, long *total)
{
    tse_geometry g;
    const int bad = geometry_of(v, &g);
    if (bad != TSE_PARAM_OK)
        return bad;
    tse_real o[3];
    to_real(orientation, o, 3);
    *status = (int)tse_workspace_count(&g, n_r, n_phi, n_z, o, reachable, total);
    return TSE_PARAM_OK;
}

int tse_py_workspace_points(const double v[TSE_PY_NPARAMS], int n_r, int n_phi, int n_z,
                            const double orientation[3], double *pose, int *status, int *scissor)
{
    tse_geometry g;
    const int bad = geometry_of(v, &g);
    if (bad != TSE_PARAM_OK)
        return bad;
    tse_real o[3];
    to_real(orientation, o, 3);
    long row = 0;
    for (int i = 0; i < n_r; ++i)
        for (int j = 0; j < n_phi; ++j)
            for (int k = 0; k < n_z; ++k, ++row) {
                tse_real p[6];
                tse_status st = tse_workspace_pose(&g, n_r, n_phi, n_z, i, j, k, o, p);
                to_double(p, pose + 6 * row, 6);
                scissor[row] = 0;
                if (st == TSE_OK) {
                    tse_ik_result r;
                    st = tse_ik(&g, p, NULL, &r);
                    scissor[row] = st == TSE_OK ? 0 : r.scissor;
                }
                status[row] = (int)st;
            }
    return TSE_PARAM_OK;
}
