/* Independent long-double reference for the TSE kinematics (see oracle.h). */
#include "oracle.h"

#include <complex.h>
#include <math.h>
#include <string.h>

#include "tse/status.h"

typedef long double complex orc_cplx;

#define ORC_PI 3.141592653589793238462643383279502884L

void orc_geom_init(orc_geom *g, const orc_params *p)
{
    memset(g, 0, sizeof *g);
    g->p = *p;
    g->l0 = p->k1 * p->L;
    g->r_act = p->k3 * p->L;
    g->r_top = p->k4 * p->L;
    g->g = (1.0L - (p->L / g->l0) * (p->L / g->l0)) / 4.0L;
    g->c = cosl(2.0L * p->eta);
    for (int i = 0; i < 3; i++) {
        orc_real beta = (orc_real)i * 2.0L * ORC_PI / 3.0L;
        orc_real cb = cosl(beta), sb = sinl(beta);
        if (i == 0) {
            cb = 1.0L;
            sb = 0.0L;
        }
        g->cb[i] = cb;
        g->sb[i] = sb;
        /* e_r = (cb, sb), e_t = (-sb, cb) */
        orc_real ce = cosl(p->eta), se = sinl(p->eta);
        g->O[i][0] = g->r_act * cb;
        g->O[i][1] = g->r_act * sb;
        g->a[i][0] = ce * -sb + se * cb;
        g->a[i][1] = ce * cb + se * sb;
        g->b[i][0] = -ce * -sb + se * cb;
        g->b[i][1] = -ce * cb + se * sb;
    }
}

static void mat3_mul(const orc_real A[3][3], const orc_real B[3][3], orc_real C[3][3])
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            orc_real s = 0.0L;
            for (int k = 0; k < 3; k++)
                s += A[i][k] * B[k][j];
            C[i][j] = s;
        }
}

static void rot_x(orc_real t, orc_real R[3][3])
{
    orc_real c = cosl(t), s = sinl(t);
    orc_real M[3][3] = {{1, 0, 0}, {0, c, -s}, {0, s, c}};
    memcpy(R, M, sizeof M);
}

static void rot_y(orc_real t, orc_real R[3][3])
{
    orc_real c = cosl(t), s = sinl(t);
    orc_real M[3][3] = {{c, 0, s}, {0, 1, 0}, {-s, 0, c}};
    memcpy(R, M, sizeof M);
}

static void rot_z(orc_real t, orc_real R[3][3])
{
    orc_real c = cosl(t), s = sinl(t);
    orc_real M[3][3] = {{c, -s, 0}, {s, c, 0}, {0, 0, 1}};
    memcpy(R, M, sizeof M);
}

/* Derivatives of the elementary rotations. */
static void drot_x(orc_real t, orc_real R[3][3])
{
    orc_real c = cosl(t), s = sinl(t);
    orc_real M[3][3] = {{0, 0, 0}, {0, -s, -c}, {0, c, -s}};
    memcpy(R, M, sizeof M);
}

static void drot_y(orc_real t, orc_real R[3][3])
{
    orc_real c = cosl(t), s = sinl(t);
    orc_real M[3][3] = {{-s, 0, c}, {0, 0, 0}, {-c, 0, -s}};
    memcpy(R, M, sizeof M);
}

static void drot_z(orc_real t, orc_real R[3][3])
{
    orc_real c = cosl(t), s = sinl(t);
    orc_real M[3][3] = {{-s, -c, 0}, {c, -s, 0}, {0, 0, 0}};
    memcpy(R, M, sizeof M);
}

static void compose(const orc_real Z[3][3], const orc_real Y[3][3], const orc_real X[3][3],
                    orc_real R[3][3])
{
    orc_real T[3][3];
    mat3_mul(Y, X, T);
    mat3_mul(Z, T, R);
}

void orc_rotation(orc_real roll, orc_real pitch, orc_real yaw, orc_real R[3][3])
{
    orc_real X[3][3], Y[3][3], Z[3][3];
    rot_x(roll, X);
    rot_y(pitch, Y);
    rot_z(yaw, Z);
    compose(Z, Y, X, R);
}

void orc_rpy(const orc_real R[3][3], orc_real *roll, orc_real *pitch, orc_real *yaw)
{
    /* R[2][0] = -sin p, R[2][1] = cos p sin r, R[2][2] = cos p cos r,
     * R[0][0] = cos y cos p, R[1][0] = sin y cos p */
    *pitch = atan2l(-R[2][0], sqrtl(R[2][1] * R[2][1] + R[2][2] * R[2][2]));
    *roll = atan2l(R[2][1], R[2][2]);
    *yaw = atan2l(R[1][0], R[0][0]);
}

void orc_joints(const orc_geom *g, const orc_real pose[6], orc_real C[3][3])
{
    orc_real R[3][3];
    orc_rotation(pose[3], pose[4], pose[5], R);
    for (int i = 0; i < 3; i++)
        for (int k = 0; k < 3; k++)
            C[i][k] = pose[k] + g->r_top * (R[k][0] * g->cb[i] + R[k][1] * g->sb[i]);
}

/* u = d.a, v = d.b, rho2 = |d|^2 for d = C - O_i */
static void uv(const orc_geom *g, int i, const orc_real C[3], orc_real *u, orc_real *v,
               orc_real *rho2, orc_real d[3])
{
    d[0] = C[0] - g->O[i][0];
    d[1] = C[1] - g->O[i][1];
    d[2] = C[2];
    *u = d[0] * g->a[i][0] + d[1] * g->a[i][1];
    *v = d[0] * g->b[i][0] + d[1] * g->b[i][1];
    *rho2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
}

void orc_residual(const orc_geom *g, int i, const orc_real C[3], orc_real sa, orc_real sb,
                  orc_real F[2], orc_real M[2][2])
{
    orc_real u, v, rho2, d[3];
    uv(g, i, C, &u, &v, &rho2, d);
    orc_real L = g->p.L, gg = g->g, c = g->c;
    F[0] = sa * sa - 2.0L * u * sa - sb * sb + 2.0L * v * sb;
    F[1] = sa * sa - 2.0L * u * sa + rho2 - L * L - gg * (sa * sa + sb * sb + 2.0L * c * sa * sb);
    M[0][0] = 2.0L * (sa - u);
    M[0][1] = -2.0L * (sb - v);
    M[1][0] = 2.0L * (sa - u) - 2.0L * gg * (sa + c * sb);
    M[1][1] = -2.0L * gg * (sb + c * sa);
}

static void fill_sol(const orc_geom *g, int i, const orc_real C[3], orc_real sa, orc_real sb,
                     orc_sol *s)
{
    orc_real F[2], M[2][2];
    orc_residual(g, i, C, sa, sb, F, M);
    s->sa = sa;
    s->sb = sb;
    s->det = M[0][0] * M[1][1] - M[0][1] * M[1][0];
    orc_real n1 = hypotl(M[0][0], M[0][1]), n2 = hypotl(M[1][0], M[1][1]);
    s->mu = (n1 > 0.0L && n2 > 0.0L) ? s->det / (n1 * n2) : 0.0L;
    s->row2 = n1 < n2 ? n1 * n1 : n2 * n2;
    orc_real w2 = sa * sa + sb * sb + 2.0L * g->c * sa * sb;
    s->w = sqrtl(w2 > 0.0L ? w2 : 0.0L);
    s->resid = fabsl(F[0]) + fabsl(F[1]);
}

/* Newton on (F1, F2) in long double from (sa, sb).  Returns 1 when the residual is at rounding
 * level of the equations. */
static int polish(const orc_geom *g, int i, const orc_real C[3], orc_real *sa, orc_real *sb)
{
    orc_real L2 = g->p.L * g->p.L;
    for (int it = 0; it < 100; it++) {
        orc_real F[2], M[2][2];
        orc_residual(g, i, C, *sa, *sb, F, M);
        orc_real det = M[0][0] * M[1][1] - M[0][1] * M[1][0];
        if (det == 0.0L || !isfinite(det))
            break;
        orc_real da = (M[1][1] * F[0] - M[0][1] * F[1]) / det;
        orc_real db = (-M[1][0] * F[0] + M[0][0] * F[1]) / det;
        *sa -= da;
        *sb -= db;
        if (fabsl(da) + fabsl(db) <= 1e-18L * (1.0L + fabsl(*sa) + fabsl(*sb)))
            break;
    }
    orc_real F[2], M[2][2];
    orc_residual(g, i, C, *sa, *sb, F, M);
    return isfinite(F[0]) && isfinite(F[1]) && fabsl(F[0]) + fabsl(F[1]) <= 1e-15L * L2;
}

/* All roots of the polynomial sum coef[k] m^k (degree n <= 4, coef[n] != 0), Durand-Kerner. */
static int poly_roots(const orc_real *coef, int n, orc_cplx *roots)
{
    orc_real mon[5];
    for (int k = 0; k <= n; k++)
        mon[k] = coef[k] / coef[n];
    orc_real bound = 0.0L;
    for (int k = 0; k < n; k++)
        if (fabsl(mon[k]) > bound)
            bound = fabsl(mon[k]);
    bound += 1.0L;
    orc_cplx z0 = 0.4L + 0.9L * I;
    orc_cplx zk = 1.0L;
    for (int k = 0; k < n; k++) {
        roots[k] = bound * zk;
        zk *= z0;
    }
    for (int it = 0; it < 5000; it++) {
        orc_real change = 0.0L;
        for (int k = 0; k < n; k++) {
            orc_cplx p = 1.0L;
            for (int j = n - 1; j >= 0; j--)
                p = p * roots[k] + mon[j];
            /* p now holds the monic polynomial value (Horner with leading 1) */
            orc_cplx den = 1.0L;
            for (int j = 0; j < n; j++)
                if (j != k)
                    den *= roots[k] - roots[j];
            if (cabsl(den) == 0.0L)
                den = 1e-30L;
            orc_cplx step = p / den;
            roots[k] -= step;
            orc_real rel = cabsl(step) / (1.0L + cabsl(roots[k]));
            if (rel > change)
                change = rel;
        }
        if (change < 1e-19L && it > 10)
            break;
    }
    return n;
}

static int same_sol(const orc_sol *x, orc_real sa, orc_real sb)
{
    return fabsl(x->sa - sa) + fabsl(x->sb - sb) <= 1e-12L * (1.0L + fabsl(sa) + fabsl(sb));
}

static void add_candidate(const orc_geom *g, int i, const orc_real C[3], orc_real sa, orc_real sb,
                          orc_scissor_set *out, int *polish_failed)
{
    if (!isfinite(sa) || !isfinite(sb))
        return;
    if (!polish(g, i, C, &sa, &sb)) {
        *polish_failed = 1;
        return;
    }
    for (int k = 0; k < out->n_real; k++)
        if (same_sol(&out->real[k], sa, sb))
            return;
    if (out->n_real < ORC_MAX_SOL)
        fill_sol(g, i, C, sa, sb, &out->real[out->n_real++]);
}

void orc_scissor(const orc_geom *g, int i, const orc_real C[3], const orc_tol *tol,
                 orc_scissor_set *out)
{
    memset(out, 0, sizeof *out);
    orc_real u, v, rho2, d[3];
    uv(g, i, C, &u, &v, &rho2, d);
    orc_real L = g->p.L, gg = g->g, c = g->c;
    orc_real delta = u * u - v * v;
    /* A delta at rounding level is the mirror-plane case (e.g. the vertical axis): there the two
     * roots m = O(delta) stand for the line a = -b, where det M < 0, and would only blur into a
     * near-double pair; drop them exactly as for delta = 0. */
    if (fabsl(delta) <= 1e-15L * (u * u + v * v + rho2))
        delta = 0.0L;
    orc_real K = rho2 - L * L - u * u;
    /* 4 m^2 F2 = (m^2 + delta)^2 + 4 m^2 K - g (P^2 + Q^2 + 2c P Q),
     * P = m^2 + 2u m + delta = 2m s_A, Q = m^2 + 2v m - delta = 2m s_B. */
    orc_real coef[5];
    coef[4] = 1.0L - gg * (2.0L + 2.0L * c);
    coef[3] = -gg * 4.0L * (1.0L + c) * (u + v);
    coef[2] = 2.0L * delta + 4.0L * K - gg * (4.0L * u * u + 4.0L * v * v + 8.0L * c * u * v);
    coef[1] = -gg * 4.0L * delta * (u - v) * (1.0L - c);
    coef[0] = delta * delta * (1.0L - 2.0L * gg * (1.0L - c));
    orc_cplx roots[4];
    int nroots;
    if (delta == 0.0L) {
        /* m^2 (coef4 m^2 + coef3 m + coef2): the double root m = 0 stands for the line a = -b,
         * where det M < 0 (kinematics.md); solve the quadratic factor only. */
        nroots = poly_roots(coef + 2, 2, roots);
    } else {
        nroots = poly_roots(coef, 4, roots);
    }
    int polish_failed = 0;
    for (int k = 0; k < nroots; k++) {
        orc_real m = creall(roots[k]);
        orc_real im = fabsl(cimagl(roots[k]));
        orc_real scale = 1.0L + fabsl(m);
        if (im > 1e-3L * scale)
            continue; /* clearly complex */
        if (m == 0.0L)
            continue;
        orc_real sa = (m * m + 2.0L * u * m + delta) / (2.0L * m);
        orc_real sb = (m * m + 2.0L * v * m - delta) / (2.0L * m);
        if (im > 1e-8L * scale) {
            /* nearly a real double root: a tangency, where det M = 0.  If it lies where the
             * branch could appear (det M ~ 0, slides not clearly negative), existence is
             * uncertain. */
            orc_sol t;
            fill_sol(g, i, C, sa, sb, &t);
            if (fabsl(t.mu) < 0.05L && sa > -0.01L && sb > -0.01L)
                out->near_boundary = 1;
            continue;
        }
        add_candidate(g, i, C, sa, sb, out, &polish_failed);
    }
    if (polish_failed)
        out->near_boundary = 1;
    for (int k = 0; k < out->n_real; k++) {
        const orc_sol *s = &out->real[k];
        int on = s->det > 0.0L && s->sa > 0.0L && s->sb > 0.0L;
        if (fabsl(s->mu) < tol->mu && s->sa > -tol->len && s->sb > -tol->len)
            out->near_boundary = 1;
        if (s->det > 0.0L && (fabsl(s->sa) < tol->len || fabsl(s->sb) < tol->len))
            out->near_boundary = 1;
        if (on)
            out->branch[out->n++] = *s;
    }
    /* largest mu first */
    for (int a = 0; a < out->n; a++)
        for (int b = a + 1; b < out->n; b++)
            if (out->branch[b].mu > out->branch[a].mu) {
                orc_sol t = out->branch[a];
                out->branch[a] = out->branch[b];
                out->branch[b] = t;
            }
}

void orc_constraint_jacobian(const orc_geom *g, const orc_real pose[6], const orc_real q[6],
                             orc_real Fp[6][6])
{
    orc_real C[3][3];
    orc_joints(g, pose, C);
    orc_real X[3][3], Y[3][3], Z[3][3], dX[3][3], dY[3][3], dZ[3][3];
    rot_x(pose[3], X);
    rot_y(pose[4], Y);
    rot_z(pose[5], Z);
    drot_x(pose[3], dX);
    drot_y(pose[4], dY);
    drot_z(pose[5], dZ);
    orc_real dR[3][3][3];
    compose(Z, Y, dX, dR[0]);
    compose(Z, dY, X, dR[1]);
    compose(dZ, Y, X, dR[2]);
    for (int i = 0; i < 3; i++) {
        orc_real sa = q[2 * i], sb = q[2 * i + 1];
        orc_real u, v, rho2, d[3];
        uv(g, i, C[i], &u, &v, &rho2, d);
        orc_real a3[3] = {g->a[i][0], g->a[i][1], 0.0L};
        orc_real b3[3] = {g->b[i][0], g->b[i][1], 0.0L};
        orc_real g1[3], g2[3]; /* dF1/dC, dF2/dC */
        for (int k = 0; k < 3; k++) {
            g1[k] = -2.0L * sa * a3[k] + 2.0L * sb * b3[k];
            g2[k] = -2.0L * sa * a3[k] + 2.0L * d[k];
        }
        for (int col = 0; col < 6; col++) {
            orc_real dC[3];
            if (col < 3) {
                for (int k = 0; k < 3; k++)
                    dC[k] = (k == col) ? 1.0L : 0.0L;
            } else {
                /* d C / d angle = r_top dR c_i; divided by r_top */
                for (int k = 0; k < 3; k++)
                    dC[k] = dR[col - 3][k][0] * g->cb[i] + dR[col - 3][k][1] * g->sb[i];
            }
            Fp[2 * i][col] = g1[0] * dC[0] + g1[1] * dC[1] + g1[2] * dC[2];
            Fp[2 * i + 1][col] = g2[0] * dC[0] + g2[1] * dC[1] + g2[2] * dC[2];
        }
    }
}

orc_real orc_hadamard(const orc_real A[6][6])
{
    orc_real W[6][6];
    orc_real prod = 1.0L;
    for (int i = 0; i < 6; i++) {
        orc_real n = 0.0L;
        for (int j = 0; j < 6; j++) {
            W[i][j] = A[i][j];
            n += A[i][j] * A[i][j];
        }
        prod *= sqrtl(n);
    }
    if (prod == 0.0L)
        return 0.0L;
    orc_real det = 1.0L;
    for (int k = 0; k < 6; k++) {
        int piv = k;
        for (int i = k + 1; i < 6; i++)
            if (fabsl(W[i][k]) > fabsl(W[piv][k]))
                piv = i;
        if (W[piv][k] == 0.0L)
            return 0.0L;
        if (piv != k) {
            for (int j = 0; j < 6; j++) {
                orc_real t = W[k][j];
                W[k][j] = W[piv][j];
                W[piv][j] = t;
            }
        }
        det *= W[k][k];
        for (int i = k + 1; i < 6; i++) {
            orc_real f = W[i][k] / W[k][k];
            for (int j = k; j < 6; j++)
                W[i][j] -= f * W[k][j];
        }
    }
    return fabsl(det) / prod;
}

static int near(orc_real x, orc_real thr, orc_real tol)
{
    return fabsl(x - thr) < tol;
}

void orc_ik(const orc_geom *g, const orc_real pose[6], const orc_real *prefer_q, const orc_tol *tol,
            orc_result *out)
{
    memset(out, 0, sizeof *out);
    out->nu = NAN;
    for (int k = 0; k < 6; k++)
        out->q[k] = NAN;
    for (int k = 0; k < 6; k++) {
        if (!isfinite(pose[k])) {
            out->status = TSE_INVALID;
            for (int i = 0; i < 3; i++)
                out->st[i] = TSE_INVALID;
            return;
        }
    }
    orc_joints(g, pose, out->C);
    const orc_params *p = &g->p;
    const orc_real span = p->L + g->r_act + g->r_top; /* tol->mu_noise's scale */
    int all_solved = 1;
    for (int i = 0; i < 3; i++) {
        orc_scissor_set set;
        orc_scissor(g, i, out->C[i], tol, &set);
        out->nsol[i] = set.n;
        if (set.near_boundary)
            out->ambiguous = 1;
        if (set.n > 1)
            out->multi = 1;
        out->mu[i] = NAN;
        out->w[i] = NAN;
        out->alpha[i] = NAN;
        int st = TSE_OK;
        if (set.n == 0) {
            st = TSE_UNREACHABLE;
            all_solved = 0;
        }
        /* C.z == 0 exactly (zero tilt at Z = 0) is below in every precision */
        if (out->C[i][2] != 0.0L && near(out->C[i][2], 0.0L, tol->len))
            out->ambiguous = 1;
        if (set.n > 0) {
            int pick = 0;
            if (prefer_q && set.n > 1) {
                orc_real best = INFINITY;
                for (int k = 0; k < set.n; k++) {
                    orc_real dd = fabsl(set.branch[k].sa - prefer_q[2 * i]) +
                                  fabsl(set.branch[k].sb - prefer_q[2 * i + 1]);
                    if (dd < best) {
                        best = dd;
                        pick = k;
                    }
                }
            }
            const orc_sol *s = &set.branch[pick];
            out->q[2 * i] = s->sa;
            out->q[2 * i + 1] = s->sb;
            out->mu[i] = s->mu;
            out->w[i] = s->w;
            orc_real ratio = s->w / (2.0L * g->l0);
            out->alpha[i] = ratio <= 1.0L ? acosl(ratio) : NAN;
            /* closeness to every threshold that is checked */
            if (near(out->alpha[i], p->alpha_min, tol->ang) ||
                near(out->alpha[i], p->alpha_max, tol->ang) || near(ratio, 1.0L, tol->ang))
                out->ambiguous = 1;
            if (near(s->sa, p->s_min, tol->len) || near(s->sa, p->s_max, tol->len) ||
                near(s->sb, p->s_min, tol->len) || near(s->sb, p->s_max, tol->len))
                out->ambiguous = 1;
            if (near(s->mu, p->mu_min, tol->mu) ||
                (s->mu > 0.0L && fabsl(s->mu - p->mu_min) * s->mu * s->row2 < tol->mu_noise * span * span))
                out->ambiguous = 1;
            if (out->C[i][2] <= 0.0L)
                st = TSE_BELOW;
            else if (!(ratio <= 1.0L) || out->alpha[i] < p->alpha_min ||
                     out->alpha[i] > p->alpha_max)
                st = TSE_ALPHA;
            else if (s->sa < p->s_min || s->sa > p->s_max || s->sb < p->s_min ||
                     s->sb > p->s_max)
                st = TSE_STROKE;
            else if (s->mu < p->mu_min)
                st = TSE_SINGULAR;
        }
        out->st[i] = st;
    }
    if (all_solved) {
        orc_real Fp[6][6];
        orc_constraint_jacobian(g, pose, out->q, Fp);
        out->nu = orc_hadamard(Fp);
    }
    /* kinematics.md: "Every rejection names the first failing scissor (1..3) and a status,
     * checked in this order": the first scissor that fails any check, with the first check it
     * fails.  Type 2 (degenerate) concerns the whole pose and comes after all three. */
    int best = TSE_OK, who = 0;
    for (int i = 0; i < 3; i++)
        if (out->st[i] != TSE_OK) {
            best = out->st[i];
            who = i + 1;
            break;
        }
    if (who) {
        out->status = best;
        out->scissor = who;
    } else {
        if (near(out->nu, p->nu_min, tol->nu))
            out->ambiguous = 1;
        out->status = out->nu < p->nu_min ? TSE_DEGENERATE : TSE_OK;
        out->scissor = 0;
    }
}

/* Vertical axis: X = Y = 0, zero orientation, so C_i = r_top e_r + z e_z and d = (r_top - r_act)
 * e_r + z e_z for every scissor: u = v = u0 = (r_top - r_act) sin(eta), rho2 = (r_top - r_act)^2
 * + z^2.  With s_A = s_B = s, F1 = 0 identically and F2 = D s^2 - 2 u0 s + (rho2 - L^2) with
 * D = 1 - 2 g (1 + c), since w^2 = 2 (1 + c) s^2.  Roots s = (u0 +- sqrt(u0^2 - D (rho2 - L^2)))
 * / D.  There M = [[2(s-u0), -2(s-u0)], [2(s-u0) - 2g(1+c)s, -2g(1+c)s]], so det M =
 * 4 (s - u0)(D s - u0): keep the root with det M > 0 and s > 0. */
orc_real orc_vertical_slide(const orc_geom *g, orc_real z)
{
    orc_real r = g->r_top - g->r_act;
    orc_real u0 = r * sinl(g->p.eta);
    orc_real rho2 = r * r + z * z;
    orc_real D = 1.0L - 2.0L * g->g * (1.0L + g->c);
    orc_real disc = u0 * u0 - D * (rho2 - g->p.L * g->p.L);
    if (disc < 0.0L)
        return NAN;
    orc_real sq = sqrtl(disc);
    orc_real cand[2] = {(u0 + sq) / D, (u0 - sq) / D};
    for (int k = 0; k < 2; k++) {
        orc_real s = cand[k];
        orc_real det = 4.0L * (s - u0) * (D * s - u0);
        if (det > 0.0L && s > 0.0L)
            return s;
    }
    return NAN;
}
