#include "kin_internal.h"
#include "scissor_core.h"
#include "tse/ik.h"
#include "tse/jacobian.h"

/* The Hadamard ratio of Fp = tse_constraint_rows(rot_scale = 1 / r_top) without forming Fp.
 *
 * Row (i, r) of Fp is (g, s Ax (rc_i x g)) with g = dF_r/dC_i, rc_i = C_i - (X, Y, Z), s = 1/r_top
 * and Ax the matrix whose rows are the roll, pitch and yaw axes; so Fp = [G | P] diag(I, s Ax^T)
 * with rows (g, rc_i x g) in [G | P], and det Fp = s^3 det(Ax) det[G | P].  A row (g, rc x g) is
 * the line through the ball joint along g; [G | P] t = 0 for a twist t = (v, w) exactly when every
 * ball joint's velocity v + w x rc_i is normal to both of its gradients, i.e. along
 * n_i = g_{i,1} x g_{i,2}; a velocity field lambda_i n_i is rigid when
 * (lambda_i n_i - lambda_j n_j) . e_ij = 0 for the three pairs, e_ij = C_i - C_j.  det[G | P] is
 * linear in each n_i (alternating and bilinear in the two rows of a ball joint) and cubic in the
 * positions, like the determinant of that 3x3 system, and the two are equal up to sign:
 *
 *     det[G | P] = -( (n_1.e_12)(n_2.e_23)(n_3.e_13) - (n_2.e_12)(n_1.e_13)(n_3.e_23) )
 *
 * (checked in exact rational arithmetic on random lines, and against the 6x6 elimination of
 * tse_hadamard_ratio by the kinematics tests).  Scaling e_ij by s and dividing by the product of
 * the six row norms gives the ratio; the norms are taken as one square root of the product of
 * their squares (the square roots and divisions, not the multiplications, are what the solve
 * waits on).  Each squared norm is at least the base width's square w_lo2, or |C - A|^2 on the
 * physical sheet, and at most a few L^2, so the product of six neither overflows nor
 * underflows, in float too.  A gradient may be scaled freely: the ratio does not depend on a
 * row's length, so the gradients are taken at half the size of constraint_rows.
 *
 * With rho_i = s rc_i (a unit vector), a row's rotation part is (axis_k . (rho_i x g))_k =
 * (g . (axis_k x rho_i))_k, and for these axes: roll (R e_x) x rho_i = R (e_x x e_r) =
 * sin(beta_i) N; pitch (-sin yaw, cos yaw, 0) x rho_i = h_i below; yaw e_z gives
 * rho_x g_y - rho_y g_x.  det(Ax) = R e_x . (cos yaw, sin yaw, 0) = cos(pitch); e_ij s =
 * rho_i - rho_j.
 *
 * type2_normal gives n_i and the product of its two rows' squared norms (0 for a zero row), from
 * the slides of scissor i, while the solver's values are at hand; type2_ratio the ratio from the
 * three. */
static inline tse_real type2_normal(const tse_geometry *g, const tse_pose_frame *f, int i,
                                    const tse_scissor_local *loc, tse_real s_a, tse_real s_b, tse_real n[3])
{
    const tse_scissor_frame *sf = &g->sc[i];
    const tse_real *rho = f->rho[i];
    const tse_real sb = sf->er[1];
    /* F1 = |AC|^2 - |BC|^2 and F2 = |AC|^2 - ..., halved gradients as in constraint_rows: g1 =
     * B - A (horizontal, |g1|^2 = w^2), g2 = C - A. */
    const tse_real aa[2] = {s_a * sf->a[0], s_a * sf->a[1]};
    const tse_real g1[2] = {s_b * sf->b[0] - aa[0], s_b * sf->b[1] - aa[1]};
    const tse_real g2[3] = {loc->d[0] - aa[0], loc->d[1] - aa[1], loc->d[2]};
    const tse_real h[3] = {f->cy * rho[2], f->sy * rho[2], -(f->sy * rho[1] + f->cy * rho[0])};
    const tse_real r1 = sb * (g1[0] * f->N[0] + g1[1] * f->N[1]);
    const tse_real p1 = g1[0] * h[0] + g1[1] * h[1];
    const tse_real y1 = rho[0] * g1[1] - rho[1] * g1[0];
    const tse_real r2 = sb * (g2[0] * f->N[0] + g2[1] * f->N[1] + g2[2] * f->N[2]);
    const tse_real p2 = g2[0] * h[0] + g2[1] * h[1] + g2[2] * h[2];
    const tse_real y2 = rho[0] * g2[1] - rho[1] * g2[0];
    const tse_real nn1 = (g1[0] * g1[0] + g1[1] * g1[1]) + (r1 * r1 + p1 * p1 + y1 * y1);
    const tse_real nn2 = (g2[0] * g2[0] + g2[1] * g2[1] + g2[2] * g2[2]) + (r2 * r2 + p2 * p2 + y2 * y2);
    n[0] = g2[2] * g1[1];
    n[1] = -(g2[2] * g1[0]);
    n[2] = g1[0] * g2[1] - g1[1] * g2[0];
    return nn1 * nn2;
}

/* The ratio from the three normals of type2_normal and the products of their rows' squared norms;
 * 0 when a row is zero (Fp singular, tse_hadamard_ratio's convention). */
static inline tse_real type2_ratio(const tse_pose_frame *f, const tse_real n[3][3], const tse_real nn[3])
{
    if (!(nn[0] > TSE_R(0.0) && nn[1] > TSE_R(0.0) && nn[2] > TSE_R(0.0)))
        return TSE_R(0.0);
    tse_real e12[3], e13[3], e23[3];
    for (int k = 0; k < 3; ++k) {
        e12[k] = f->rho[0][k] - f->rho[1][k];
        e13[k] = f->rho[0][k] - f->rho[2][k];
        e23[k] = f->rho[1][k] - f->rho[2][k];
    }
#define DOT3(x, y) ((x)[0] * (y)[0] + (x)[1] * (y)[1] + (x)[2] * (y)[2])
    const tse_real det_k = DOT3(n[0], e12) * DOT3(n[1], e23) * DOT3(n[2], e13) -
                           DOT3(n[1], e12) * DOT3(n[0], e13) * DOT3(n[2], e23);
#undef DOT3
    return tse_fabs(det_k * f->cp) / tse_sqrt(nn[0] * nn[1] * nn[2]);
}

/* The per-scissor checks of kinematics.md, in its order, on a branch solution. */
static tse_status check_scissor(const tse_geometry *g, const tse_real C[3], const tse_scissor_solution *s)
{
    if (!(C[2] > TSE_R(0.0)))
        return TSE_BELOW;
    /* w_hi = 2 l0 cos(alpha_min) < 2 l0, so this band also enforces w <= 2 l0. */
    if (!(s->w >= g->w_lo && s->w <= g->w_hi))
        return TSE_ALPHA;
    if (!(s->s_a >= g->p.s_min && s->s_a <= g->p.s_max && s->s_b >= g->p.s_min && s->s_b <= g->p.s_max))
        return TSE_STROKE;
    if (!scissor_mu_clear(g, s))
        return TSE_SINGULAR;
    return TSE_OK;
}

static tse_status reject(tse_ik_result *out, tse_status st, int scissor)
{
    out->status = st;
    out->scissor = scissor;
    return st;
}

/* Whether every x[k] is finite: x * 0 is 0 for a finite x and NaN for an infinity or a NaN, and
 * a sum of zeros stays zero.  One multiply-add per value instead of a test and a branch. */
static int all_finite(const tse_real *x, int n)
{
    tse_real z = TSE_R(0.0);
    for (int k = 0; k < n; ++k)
        z += x[k] * TSE_R(0.0);
    return z == TSE_R(0.0);
}

/* Fills out for a non-finite pose or seed, which reaches every scissor: the first failing one is
 * scissor 1. */
static tse_status invalid(tse_ik_result *out)
{
    for (int k = 0; k < 6; ++k)
        out->q[k] = (tse_real)NAN;
    for (int i = 0; i < 3; ++i) {
        out->mu[i] = (tse_real)NAN;
        for (int k = 0; k < 3; ++k)
            out->C[i][k] = (tse_real)NAN;
    }
    out->nu = (tse_real)NAN;
    out->iterations = 0;
    out->fallbacks = 0;
    return reject(out, TSE_INVALID, 1);
}

/* Newton from the seed for the scissors from `from` on that the warm pass does not settle (all of
 * them from home), side by side: one evaluation of each in turn (scissor_newton_pass), which an
 * out-of-order core overlaps, each ending as scissor_solve_fast would alone.  verdict[i] is
 * scissor_newton's (1: sol[i] is the solution, its iteration count in run[i]; 0: Newton ended at
 * run[i]'s slides, not on one inside the limits; -1: it gave up), or 0 for a ball joint beyond any
 * reach. */
typedef struct {
    tse_scissor_solution sol[3];
    scissor_run run[3];
    int verdict[3];
} side_newton;

static TSE_ALWAYS_INLINE void newton_side_by_side(const tse_geometry *g, const tse_scissor_local loc[3],
                                                  const scissor_warm warm[3], const tse_real seed[6],
                                                  int warm_pass, int from, side_newton *nw)
{
    const int flags = SCISSOR_LIMITS | SCISSOR_SKIP_WIDTH;
    scissor_consts kc[3];
    unsigned going = 0; /* bit i: scissor i's Newton goes on */
    /* Over all three (a fixed count: fewer instructions than from `from`), those before it idle. */
    for (int i = 0; i < 3; ++i) {
        int iterations;
        nw->verdict[i] = 0;
        if (i < from)
            continue;
        nw->run[i] = (scissor_run){seed[2 * i], seed[2 * i + 1], 0, 0};
        /* Scissor `from` is here because its warm pass did not settle. */
        if (warm_pass && i > from &&
            scissor_warm_end(g, &loc[i], seed[2 * i], seed[2 * i + 1], &warm[i], flags, &iterations, &nw->sol[i])) {
            nw->verdict[i] = 1;
        } else if (loc[i].rho2 <= g->reach2) {
            scissor_consts_of(g, &loc[i], &kc[i]);
            going |= 1u << i; /* its verdict comes from its last pass */
        }
    }
    while (going) {
        for (int i = 0; i < 3; ++i) {
            if (!(going & (1u << i)))
                continue;
            nw->verdict[i] =
                scissor_newton_pass(g, &kc[i], loc[i].rho2, TSE_NEWTON_MAX_ITER, flags, &nw->run[i], &nw->sol[i]);
            if (nw->verdict[i] != SCISSOR_GOING)
                going &= ~(1u << i);
        }
    }
}

TSE_FMA_CLONES
tse_status tse_ik(const tse_geometry *g, const tse_real pose[6], const tse_real seed_q[6],
                  tse_ik_result *out)
{
    out->status = TSE_OK;
    out->scissor = 0;
    out->nu = (tse_real)NAN;
    out->iterations = 0;
    out->fallbacks = 0;

    /* A non-finite pose or seed is looked for only once a scissor's Newton from its seed fails,
     * which it always makes it do: a NaN or an infinity in the pose reaches every ball joint (the
     * sine and cosine of an infinity are NaN), and in either the evaluation at the seed gives a
     * non-finite step, which ends Newton at once (scissor_newton).  A finite pose gives finite
     * ball joints (|r_top R e| <= r_top). */
    tse_pose_frame frame;
    tse_pose_frame_of(pose, &frame);
    for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k)
            out->C[i][k] = pose[k] + g->r_top * frame.rho[i][k];

    /* On an out-of-order core (TSE_SIDE_BY_SIDE) the three scissors are solved side by side: with
     * a seed, Newton's first pass (scissor_warm_steps), which from a warm seed is the whole solve;
     * whatever that leaves, and everything from home, newton_side_by_side.  On the board, one
     * after the other (scissor_solve_fast).  The answers are the same bit for bit. */
    tse_scissor_local loc[3];
    scissor_warm warm[3];
    tse_real seed[6];
    const int side_by_side = TSE_SIDE_BY_SIDE && seed_q != NULL;
    for (int k = 0; k < 6; ++k)
        seed[k] = seed_q ? seed_q[k] : g->home_s;
    for (int i = 0; i < 3; ++i)
        scissor_localize_inline(&g->sc[i], out->C[i], &loc[i]);
    if (side_by_side)
        for (int i = 0; i < 3; ++i)
            scissor_warm_steps(g, &loc[i], seed[2 * i], seed[2 * i + 1], &warm[i]);

    /* All three are solved even after a failure, so that a rejection still shows every slide. */
    const int flags = SCISSOR_LIMITS | SCISSOR_SKIP_WIDTH;
    tse_status first = TSE_OK;
    int first_scissor = 0, inputs_checked = 0, newton_run = 0;
    side_newton nw;
    tse_real n[3][3], nn[3];
    for (int i = 0; i < 3; ++i) {
        tse_scissor_solution sol;
        const tse_real seed_a = seed[2 * i], seed_b = seed[2 * i + 1];
        tse_status st = TSE_OK;
        int iterations, solved;
        tse_real a = seed_a, b = seed_b; /* where Newton got to, for the fallback */
        if (!TSE_SIDE_BY_SIDE) {
            solved = scissor_solve_fast(g, &loc[i], &a, &b, 1, &iterations, &sol);
        } else if (!newton_run && side_by_side &&
                   scissor_warm_end(g, &loc[i], seed_a, seed_b, &warm[i], flags, &iterations, &sol)) {
            solved = 1;
        } else {
            if (!newton_run) {
                newton_side_by_side(g, loc, warm, seed, side_by_side, i, &nw);
                newton_run = 1;
            }
            solved = nw.verdict[i] == 1;
            iterations = nw.run[i].iterations;
            /* What the rest reads of a solution without the fallback (a whole copy costs more). */
            sol.s_a = nw.sol[i].s_a;
            sol.s_b = nw.sol[i].s_b;
            sol.mu = nw.sol[i].mu;
            sol.n_min = nw.sol[i].n_min;
            sol.iterations = iterations;
            sol.fallback = 0;
            /* Newton that gave up leaves the seed to the fallback, one that ended, its end. */
            if (nw.verdict[i] >= 0) {
                a = nw.run[i].a;
                b = nw.run[i].b;
            }
        }
        if (!solved) {
            if (!inputs_checked) {
                if (!all_finite(pose, 6) || (seed_q != NULL && !all_finite(seed_q, 6)))
                    return invalid(out);
                inputs_checked = 1;
            }
            /* Its own struct: sol, whose address then never leaves this function, can live in
             * registers on the common path. */
            tse_scissor_solution fb;
            st = tse_scissor_fallback(g, &loc[i], seed_a, seed_b, a, b, iterations, &fb);
            sol = fb;
        }
        out->iterations += sol.iterations;
        out->fallbacks += sol.fallback;
        if (st == TSE_OK) {
            out->q[2 * i] = sol.s_a;
            out->q[2 * i + 1] = sol.s_b;
            out->mu[i] = sol.mu;
            if (sol.fallback)
                st = check_scissor(g, out->C[i], &sol);
            else if (!(out->C[i][2] > TSE_R(0.0)))
                st = TSE_BELOW;
            /* Without the fallback the solution is inside the stroke and the stops already. */
            else if (!scissor_mu_clear(g, &sol))
                st = TSE_SINGULAR;
            if (st == TSE_OK)
                nn[i] = type2_normal(g, &frame, i, &loc[i], sol.s_a, sol.s_b, n[i]);
        } else {
            out->q[2 * i] = (tse_real)NAN;
            out->q[2 * i + 1] = (tse_real)NAN;
            out->mu[i] = (tse_real)NAN;
        }
        if (st != TSE_OK && first == TSE_OK) {
            first = st;
            first_scissor = i + 1;
        }
    }
    if (first != TSE_OK)
        return reject(out, first, first_scissor);

    /* Type 2: rotation columns in metres of ball-joint travel, so that they weigh like the
     * translation columns whatever the plate size. */
    out->nu = type2_ratio(&frame, (const tse_real(*)[3])n, nn);
    if (!(out->nu >= g->p.nu_min)) {
        tse_plate plate;
        tse_real Fp[6][6];
        tse_plate_frame(pose, &plate);
        tse_constraint_rows(g, pose, &plate, out->C, out->q, g->inv_r_top, Fp, NULL);
        const int row = tse_weakest_row6(Fp);
        return reject(out, TSE_DEGENERATE, row < 0 ? 1 : row / 2 + 1);
    }
    return TSE_OK;
}
