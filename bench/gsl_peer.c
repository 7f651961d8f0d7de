/* A C peer for the inverse kinematics benchmark: what a C engineer would write with GSL instead of
 * tse_ik_d, timed against it in the same run.
 *
 * Per pose: the ball joints C_i from the library (tse_apex_points, so both sides start from the
 * same inputs), then per scissor gsl_multiroot_fdfsolver_newton on the contract's F1, F2
 * (kinematics.md, "Constraint equations of one scissor") with the analytic Jacobian M, stopped by
 * gsl_multiroot_test_delta(dx, x, 1e-12, 0): Newton's last step bounds the error left, so the
 * slides are well inside the contract's 1e-9 m in double.
 *   warm: seeded with the previous pose's slides (the first pose with its own cold solution),
 *   cold: every slide seeded with the home slides g.home_s, as tse_ik's cold start.
 * Ours is tse_ik_d, seeded the same way.  It does more than the peer: the stops, the stroke, the
 * type-1 margin mu and the type-2 margin nu (a 6x6 determinant) of the contract, and a fallback
 * that cannot miss; the peer only solves the equations.
 *
 * Poses: the 2000-pose Lissajous path of `tse-kin bench` and bench/fsolve_baseline.py (pose k at
 * t = 0.002 k), prototype design (tse_params_default).
 *
 * Timing: this VM's clock speed drifts, so the four batches (ours and GSL's, warm and cold) are
 * interleaved in each of `rounds` rounds; a batch is one pass over the path timed with
 * CLOCK_MONOTONIC, in ns per pose.  Printed: the median over the rounds of each, and the ratio
 * GSL / ours as the median over the rounds of the ratio within a round.  Nothing is asserted
 * about time.
 *
 * Agreement: GSL's slides against ours on every pose ours accepts (max |dq|), and the poses ours
 * accepts where GSL failed or landed off the physical sheet (det M > 0, positive slides).  Exit
 * status 1 when they differ by more than 1e-8 m or GSL missed a pose; 2 on a usage or set-up
 * error.
 *
 * Usage: gsl-peer [poses [rounds]]   (defaults 2000, 21).  Output: `name,value` lines and `#`
 * comments. */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_matrix.h>
#include <gsl/gsl_multiroots.h>
#include <gsl/gsl_vector.h>

#include "bench_clock.h"
#include "tse/geometry.h"
#include "tse/ik.h"
#include "tse/params.h"

enum { PEER_MAX_ITER = 50 };
#define PEER_EPSABS 1e-12  /* m: gsl_multiroot_test_delta's absolute bound on the last step */
#define AGREE_TOL 1e-8     /* m: the answers must agree this well, or the run fails */

/* What F1, F2 of one scissor depend on besides the slides. */
typedef struct {
    double u, v, rho2; /* d . a_i, d . b_i, |d|^2 with d = C_i - O_i */
    double g, c, LL;   /* (1 - (L/l0)^2) / 4, cos(2 eta), L^2 */
} scissor_terms;

static void terms_of(const tse_geometry *g, int i, const double C[3], scissor_terms *t)
{
    const tse_scissor_frame *f = &g->sc[i];
    const double dx = C[0] - f->o[0], dy = C[1] - f->o[1], dz = C[2];
    t->u = dx * f->a[0] + dy * f->a[1];
    t->v = dx * f->b[0] + dy * f->b[1];
    t->rho2 = dx * dx + dy * dy + dz * dz;
    t->g = g->g;
    t->c = g->c;
    t->LL = g->p.L * g->p.L;
}

/* F1 = s_A^2 - 2u s_A - s_B^2 + 2v s_B,  F2 = s_A^2 - 2u s_A + rho2 - L^2 - g (s_A^2 + s_B^2 + 2c s_A s_B). */
static void residual(const scissor_terms *t, double sa, double sb, double F[2])
{
    const double a2 = sa * sa - 2.0 * t->u * sa;
    F[0] = a2 - sb * sb + 2.0 * t->v * sb;
    F[1] = a2 + t->rho2 - t->LL - t->g * (sa * sa + sb * sb + 2.0 * t->c * sa * sb);
}

/* M = [2(s_A - u), -2(s_B - v); 2(s_A - u) - 2g(s_A + c s_B), -2g(s_B + c s_A)]. */
static void jacobian(const scissor_terms *t, double sa, double sb, double M[2][2])
{
    M[0][0] = 2.0 * (sa - t->u);
    M[0][1] = -2.0 * (sb - t->v);
    M[1][0] = 2.0 * (sa - t->u) - 2.0 * t->g * (sa + t->c * sb);
    M[1][1] = -2.0 * t->g * (sb + t->c * sa);
}

static int gsl_f(const gsl_vector *x, void *params, gsl_vector *f)
{
    double F[2];
    residual(params, gsl_vector_get(x, 0), gsl_vector_get(x, 1), F);
    gsl_vector_set(f, 0, F[0]);
    gsl_vector_set(f, 1, F[1]);
    return GSL_SUCCESS;
}

static int gsl_df(const gsl_vector *x, void *params, gsl_matrix *J)
{
    double M[2][2];
    jacobian(params, gsl_vector_get(x, 0), gsl_vector_get(x, 1), M);
    for (size_t r = 0; r < 2; ++r)
        for (size_t k = 0; k < 2; ++k)
            gsl_matrix_set(J, r, k, M[r][k]);
    return GSL_SUCCESS;
}

static int gsl_fdf(const gsl_vector *x, void *params, gsl_vector *f, gsl_matrix *J)
{
    gsl_f(x, params, f);
    return gsl_df(x, params, J);
}

/* One solver per scissor, allocated once: a pose then costs no allocation. */
typedef struct {
    const tse_geometry *g;
    gsl_multiroot_fdfsolver *s[3];
    gsl_vector *x0;
    scissor_terms t[3];
    gsl_multiroot_function_fdf fn[3];
    long iterations; /* Newton iterations, over all scissors and poses since the last reset */
} peer;

static int peer_init(peer *p, const tse_geometry *g)
{
    memset(p, 0, sizeof *p);
    p->g = g;
    p->x0 = gsl_vector_alloc(2);
    if (!p->x0)
        return -1;
    for (int i = 0; i < 3; ++i) {
        p->s[i] = gsl_multiroot_fdfsolver_alloc(gsl_multiroot_fdfsolver_newton, 2);
        if (!p->s[i])
            return -1;
        p->fn[i] = (gsl_multiroot_function_fdf){gsl_f, gsl_df, gsl_fdf, 2, &p->t[i]};
    }
    return 0;
}

static void peer_free(peer *p)
{
    for (int i = 0; i < 3; ++i)
        if (p->s[i])
            gsl_multiroot_fdfsolver_free(p->s[i]);
    if (p->x0)
        gsl_vector_free(p->x0);
}

/* The slides of one pose from seed[6] into q[6].  Returns 1 when every scissor converged; q then
 * holds GSL's roots (not yet checked for the branch). */
static int peer_solve(peer *p, const double pose[6], const double seed[6], double q[6])
{
    double C[3][3];
    tse_apex_points(p->g, pose, C);
    int ok = 1;
    for (int i = 0; i < 3; ++i) {
        terms_of(p->g, i, C[i], &p->t[i]);
        gsl_vector_set(p->x0, 0, seed[2 * i]);
        gsl_vector_set(p->x0, 1, seed[2 * i + 1]);
        gsl_multiroot_fdfsolver *s = p->s[i];
        int status = gsl_multiroot_fdfsolver_set(s, &p->fn[i], p->x0);
        int iter = 0;
        while (status == GSL_SUCCESS && iter < PEER_MAX_ITER) {
            ++iter;
            status = gsl_multiroot_fdfsolver_iterate(s);
            if (status != GSL_SUCCESS)
                break;
            status = gsl_multiroot_test_delta(s->dx, s->x, PEER_EPSABS, 0.0);
            if (status == GSL_SUCCESS)
                break;
            status = GSL_SUCCESS; /* GSL_CONTINUE: iterate again */
        }
        p->iterations += iter;
        const int converged = status == GSL_SUCCESS && iter < PEER_MAX_ITER;
        q[2 * i] = gsl_vector_get(s->x, 0);
        q[2 * i + 1] = gsl_vector_get(s->x, 1);
        ok &= converged;
    }
    return ok;
}

/* Whether q solves the pose on the contract's branch: every scissor with det M > 0 and positive
 * slides (the residual is Newton's business: it converged). */
static int on_sheet(const tse_geometry *g, const double pose[6], const double q[6])
{
    double C[3][3];
    tse_apex_points(g, pose, C);
    for (int i = 0; i < 3; ++i) {
        scissor_terms t;
        double M[2][2];
        terms_of(g, i, C[i], &t);
        const double sa = q[2 * i], sb = q[2 * i + 1];
        jacobian(&t, sa, sb, M);
        if (!(isfinite(sa) && isfinite(sb) && sa > 0.0 && sb > 0.0 && M[0][0] * M[1][1] - M[0][1] * M[1][0] > 0.0))
            return 0;
    }
    return 1;
}

static volatile double bench_sink;

/* One pass of ours over the path; q (n x 6) receives the slides.  Warm: seeded with the last
 * accepted solution, starting from first_seed; cold: seed_q NULL (home).  Returns ns per pose. */
static double ours_pass(const tse_geometry *g, const double (*poses)[6], int n, const double *first_seed,
                        double (*q)[6], int *ok)
{
    double seed[6], acc = 0.0;
    if (first_seed)
        memcpy(seed, first_seed, sizeof seed);
    tse_ik_result r;
    const double t0 = bench_now_ns();
    for (int k = 0; k < n; ++k) {
        const tse_status st = tse_ik(g, poses[k], first_seed ? seed : NULL, &r);
        if (first_seed && st == TSE_OK)
            memcpy(seed, r.q, sizeof seed);
        memcpy(q[k], r.q, sizeof seed);
        ok[k] = st == TSE_OK;
        acc += r.q[0];
    }
    const double t1 = bench_now_ns();
    bench_sink = acc;
    return (t1 - t0) / n;
}

/* The same for the peer.  Warm: seeded with its last converged solution from first_seed; cold:
 * every slide at g.home_s. */
static double peer_pass(peer *p, const double (*poses)[6], int n, const double *first_seed, double (*q)[6],
                        int *ok)
{
    double seed[6], acc = 0.0;
    if (first_seed)
        memcpy(seed, first_seed, sizeof seed);
    else
        for (int k = 0; k < 6; ++k)
            seed[k] = p->g->home_s;
    const double t0 = bench_now_ns();
    for (int k = 0; k < n; ++k) {
        ok[k] = peer_solve(p, poses[k], seed, q[k]);
        if (first_seed && ok[k])
            memcpy(seed, q[k], sizeof seed);
        acc += q[k][0];
    }
    const double t1 = bench_now_ns();
    bench_sink = acc;
    return (t1 - t0) / n;
}

/* Max |dq| over the poses ours accepts; *missed counts those where the peer failed or left the
 * branch. */
static double compare(const tse_geometry *g, const double (*poses)[6], int n, double (*q_ours)[6],
                      const int *ok_ours, double (*q_peer)[6], const int *ok_peer, int *missed, int *accepted)
{
    double worst = 0.0;
    *missed = 0;
    *accepted = 0;
    for (int k = 0; k < n; ++k) {
        if (!ok_ours[k])
            continue;
        ++*accepted;
        if (!ok_peer[k] || !on_sheet(g, poses[k], q_peer[k])) {
            ++*missed;
            continue;
        }
        for (int j = 0; j < 6; ++j) {
            const double d = fabs(q_peer[k][j] - q_ours[k][j]);
            worst = d > worst ? d : worst;
        }
    }
    return worst;
}

static int parse_count(const char *s, int lo, int hi, int *out)
{
    char *end;
    const long v = strtol(s, &end, 10);
    if (end == s || *end != '\0' || v < lo || v > hi)
        return -1;
    *out = (int)v;
    return 0;
}

int main(int argc, char **argv)
{
    int n = 2000, rounds = 21;
    if (argc > 3 || (argc > 1 && parse_count(argv[1], 2, 1000000, &n) != 0) ||
        (argc > 2 && parse_count(argv[2], 1, 10000, &rounds) != 0)) {
        fprintf(stderr, "usage: %s [poses (2..1000000, default 2000) [rounds (1..10000, default 21)]]\n", argv[0]);
        return 2;
    }
    gsl_set_error_handler_off(); /* a failed solve is a status, not an abort */

    tse_params prm;
    tse_params_default(&prm);
    tse_geometry g;
    if (tse_geometry_init(&g, &prm) != TSE_PARAM_OK) {
        fprintf(stderr, "gsl-peer: the default parameters are refused\n");
        return 2;
    }

    double(*poses)[6] = malloc(sizeof(double[6]) * (size_t)n);
    double(*q_ours_w)[6] = malloc(sizeof(double[6]) * (size_t)n), (*q_ours_c)[6] = malloc(sizeof(double[6]) * (size_t)n);
    double(*q_peer_w)[6] = malloc(sizeof(double[6]) * (size_t)n), (*q_peer_c)[6] = malloc(sizeof(double[6]) * (size_t)n);
    int *ok = malloc(sizeof(int) * 4 * (size_t)n);
    double *t = malloc(sizeof(double) * 6 * (size_t)rounds);
    peer p;
    if (!poses || !q_ours_w || !q_ours_c || !q_peer_w || !q_peer_c || !ok || !t || peer_init(&p, &g) != 0) {
        fprintf(stderr, "gsl-peer: out of memory\n");
        return 2;
    }
    int *ok_ours_w = ok, *ok_ours_c = ok + n, *ok_peer_w = ok + 2 * (size_t)n, *ok_peer_c = ok + 3 * (size_t)n;

    /* The path of `tse-kin bench` (cmd_bench.c) and fsolve_baseline.py. */
    for (int k = 0; k < n; ++k) {
        const double s = 0.002 * (double)k;
        poses[k][0] = 0.15 * sin(s);
        poses[k][1] = 0.12 * sin(1.7 * s);
        poses[k][2] = 1.0 + 0.3 * sin(0.5 * s);
        poses[k][3] = 0.08 * sin(1.3 * s);
        poses[k][4] = 0.06 * sin(0.9 * s);
        poses[k][5] = 0.2 * sin(0.7 * s);
    }

    /* Untimed passes: each side's first warm seed is its own cold solution of pose 0; the answers
     * and iteration counts. */
    ours_pass(&g, (const double(*)[6])poses, n, NULL, q_ours_c, ok_ours_c);
    double seed_ours[6], seed_peer[6];
    memcpy(seed_ours, q_ours_c[0], sizeof seed_ours);
    p.iterations = 0;
    peer_pass(&p, (const double(*)[6])poses, n, NULL, q_peer_c, ok_peer_c);
    const double peer_iter_cold = (double)p.iterations / n;
    memcpy(seed_peer, q_peer_c[0], sizeof seed_peer);
    ours_pass(&g, (const double(*)[6])poses, n, seed_ours, q_ours_w, ok_ours_w);
    p.iterations = 0;
    peer_pass(&p, (const double(*)[6])poses, n, seed_peer, q_peer_w, ok_peer_w);
    const double peer_iter_warm = (double)p.iterations / n;
    long ours_it_w = 0, ours_it_c = 0;
    {
        double seed[6];
        memcpy(seed, seed_ours, sizeof seed);
        tse_ik_result r;
        for (int k = 0; k < n; ++k) {
            tse_ik(&g, poses[k], NULL, &r);
            ours_it_c += r.iterations;
            if (tse_ik(&g, poses[k], seed, &r) == TSE_OK)
                memcpy(seed, r.q, sizeof seed);
            ours_it_w += r.iterations;
        }
    }

    int missed_w, missed_c, acc_w, acc_c;
    const double dq_w = compare(&g, (const double(*)[6])poses, n, q_ours_w, ok_ours_w, q_peer_w, ok_peer_w,
                                &missed_w, &acc_w);
    const double dq_c = compare(&g, (const double(*)[6])poses, n, q_ours_c, ok_ours_c, q_peer_c, ok_peer_c,
                                &missed_c, &acc_c);

    /* Timed: the four batches interleaved in every round. */
    double *ow = t, *pw = t + rounds, *oc = t + 2 * (size_t)rounds, *pc = t + 3 * (size_t)rounds;
    double *rw = t + 4 * (size_t)rounds, *rc = t + 5 * (size_t)rounds;
    for (int r = 0; r < rounds; ++r) {
        ow[r] = ours_pass(&g, (const double(*)[6])poses, n, seed_ours, q_ours_w, ok_ours_w);
        pw[r] = peer_pass(&p, (const double(*)[6])poses, n, seed_peer, q_peer_w, ok_peer_w);
        oc[r] = ours_pass(&g, (const double(*)[6])poses, n, NULL, q_ours_c, ok_ours_c);
        pc[r] = peer_pass(&p, (const double(*)[6])poses, n, NULL, q_peer_c, ok_peer_c);
        rw[r] = pw[r] / ow[r];
        rc[r] = pc[r] / oc[r];
    }

    printf("# gsl-peer: tse_ik_d against GSL's Newton (gsl_multiroot_fdfsolver_newton, analytic Jacobian,\n"
           "# test_delta epsabs %.0e m) per scissor, on the ball joints of tse_apex_points; %d poses of the\n"
           "# tse-kin bench path, prototype design; %d rounds, each timing ours and GSL's warm and cold\n"
           "# batches in turn; ns per 6-DOF pose, medians over the rounds; ratio = median of GSL / ours\n"
           "# within a round.  Ours also checks the stops, stroke, mu and nu; GSL's side only solves.\n",
           PEER_EPSABS, n, rounds);
    printf("poses,%d\nrounds,%d\n", n, rounds);
    printf("ours_warm_ns,%.1f\ngsl_warm_ns,%.1f\nratio_warm,%.2f\n", bench_median(ow, rounds), bench_median(pw, rounds),
           bench_median(rw, rounds));
    printf("ours_cold_ns,%.1f\ngsl_cold_ns,%.1f\nratio_cold,%.2f\n", bench_median(oc, rounds), bench_median(pc, rounds),
           bench_median(rc, rounds));
    printf("# Newton iterations per 6-DOF pose (three scissors), mean\n");
    printf("ours_iter_warm,%.2f\ngsl_iter_warm,%.2f\nours_iter_cold,%.2f\ngsl_iter_cold,%.2f\n",
           (double)ours_it_w / n, peer_iter_warm, (double)ours_it_c / n, peer_iter_cold);
    printf("# agreement on the poses ours accepts: max |q_gsl - q_ours| [m]; poses where GSL failed or left\n"
           "# the det M > 0 sheet (must be 0); the run fails above %.0e m\n",
           AGREE_TOL);
    printf("ours_ok_warm,%d\nours_ok_cold,%d\n", acc_w, acc_c);
    printf("max_dq_warm_m,%.3e\nmax_dq_cold_m,%.3e\n", dq_w, dq_c);
    printf("gsl_missed_warm,%d\ngsl_missed_cold,%d\n", missed_w, missed_c);

    const int agree = dq_w <= AGREE_TOL && dq_c <= AGREE_TOL && missed_w == 0 && missed_c == 0;
    if (!agree)
        printf("# FAIL: GSL's answers and ours disagree\n");
    peer_free(&p);
    free(poses);
    free(q_ours_w);
    free(q_ours_c);
    free(q_peer_w);
    free(q_peer_c);
    free(ok);
    free(t);
    return agree ? 0 : 1;
}
