/* The argument is in tse/enclose.h; this file is its arithmetic. */
#include "tse/enclose.h"

/* What tse_ik's answer may be off by (kinematics.md's accuracy).  The checks are proven for every
 * slide within this of the box, so that the solver's own error cannot fail a point proven here. */
#if defined(TSE_REAL_FLOAT) && TSE_REAL_FLOAT
#define IK_ACCURACY TSE_R(2e-6)
#else
#define IK_ACCURACY TSE_R(1e-9)
#endif

/* Midpoint-radius interval: every value it stands for lies in [c - r, c + r]. */
typedef struct {
    tse_real c, r;
} ci;

/* Each operation's rounding: a few units in the last place of its midpoint and of its radius. */
#define WIDEN (TSE_R(4.0) * TSE_REAL_EPS)

static inline ci mk(tse_real c, tse_real r)
{
    const ci x = {c, r};
    return x;
}

static inline ci widened(tse_real c, tse_real r)
{
    return mk(c, r * (TSE_R(1.0) + WIDEN) + WIDEN * tse_fabs(c));
}

static inline ci add(ci x, ci y)
{
    return widened(x.c + y.c, x.r + y.r);
}

static inline ci sub(ci x, ci y)
{
    return widened(x.c - y.c, x.r + y.r);
}

static inline ci mul(ci x, ci y)
{
    return widened(x.c * y.c, tse_fabs(x.c) * y.r + tse_fabs(y.c) * x.r + x.r * y.r);
}

static inline ci scale(tse_real k, ci x)
{
    return widened(k * x.c, tse_fabs(k) * x.r);
}

static inline ci sqr(ci x)
{
    return widened(x.c * x.c, TSE_R(2.0) * tse_fabs(x.c) * x.r + x.r * x.r);
}

/* x / d for a d that is positive throughout (d.c - d.r > 0). */
static inline ci divp(ci x, ci d)
{
    const tse_real lo = d.c - d.r;
    return widened(x.c / d.c, x.r / lo + tse_fabs(x.c) * d.r / (lo * d.c));
}

static inline tse_real sup(ci x)
{
    return tse_fabs(x.c) + x.r;
}

/* The least |value| the interval stands for. */
static inline tse_real mig(ci x)
{
    const tse_real m = tse_fabs(x.c) - x.r;
    return m > TSE_R(0.0) ? m : TSE_R(0.0);
}

static inline tse_real dot3(const tse_real x[3], const tse_real y[3])
{
    return x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
}

static inline tse_real norm3(const tse_real x[3])
{
    return tse_sqrt(dot3(x, x));
}

static inline void cross3(const tse_real x[3], const tse_real y[3], tse_real out[3])
{
    out[0] = x[1] * y[2] - x[2] * y[1];
    out[1] = x[2] * y[0] - x[0] * y[2];
    out[2] = x[0] * y[1] - x[1] * y[0];
}

/* How the ball joint of one scissor moves over the piece. */
typedef struct {
    tse_real rho;     /* |C(u) - C(u_c)| <= rho */
    tse_real d1[3];   /* C'(u_c) */
    tse_real rho1;    /* |C'(u) - C'(u_c)| <= rho1 */
    tse_real d2[3];   /* C''(u_c) */
    tse_real rho2;    /* |C''(u) - C''(u_c)| <= rho2 */
} joint_motion;

/* What one scissor's box leaves for the type-2 bound. */
typedef struct {
    tse_real r[2];    /* box half-widths of s_A, s_B */
    tse_real d[3];    /* C - O at the centre */
    tse_real rho;     /* the ball joint's travel over the piece (joint_motion's) */
} scissor_box;

/* One scissor over the piece: encloses its solution (returns 1), sets *failed to the first check
 * the box fails (TSE_OK when it passes them all), and bounds the slides' derivatives along u. */
static int enclose_scissor(const tse_geometry *g, int i, const tse_real C[3], const tse_real s[2],
                           const joint_motion *jm, scissor_box *box, tse_status *failed, tse_real dq[2],
                           tse_real ddq[2], tse_real dq_c[2], tse_real ddq_c[2])
{
    const tse_scissor_frame *f = &g->sc[i];
    const tse_real gg = g->g, c = g->c, L = g->p.L, rho = jm->rho;
    tse_real *d = box->d;
    box->rho = rho;
    d[0] = C[0] - f->o[0];
    d[1] = C[1] - f->o[1];
    d[2] = C[2];
    const tse_real uc = d[0] * f->a[0] + d[1] * f->a[1];
    const tse_real vc = d[0] * f->b[0] + d[1] * f->b[1];
    const tse_real dn2 = dot3(d, d), dn = tse_sqrt(dn2);
    const tse_real sa = s[0], sb = s[1];
    const tse_real w2 = sa * sa + sb * sb + TSE_R(2.0) * c * sa * sb;

    /* M at the centre; the physical sheet has det M > 0. */
    const tse_real m00 = TSE_R(2.0) * (sa - uc), m01 = TSE_R(-2.0) * (sb - vc);
    const tse_real m10 = m00 - TSE_R(2.0) * gg * (sa + c * sb), m11 = TSE_R(-2.0) * gg * (sb + c * sa);
    const tse_real det = m00 * m11 - m01 * m10;
    if (!(det > TSE_R(0.0)) || !isfinite(det))
        return 0;
    const tse_real y00 = m11 / det, y01 = -m01 / det, y10 = -m10 / det, y11 = m00 / det;
    const tse_real ay00 = tse_fabs(y00), ay01 = tse_fabs(y01), ay10 = tse_fabs(y10), ay11 = tse_fabs(y11);

    /* F at the centre slides, for every ball joint of the piece (u and v move by at most rho, the
     * squared distance |d|^2 by 2 |d| rho + rho^2), plus the rounding of terms of this size. */
    const tse_real fpad = TSE_R(16.0) * TSE_REAL_EPS * (dn2 + L * L + tse_fabs(gg) * w2 + sa * sa + sb * sb);
    const tse_real f1c = sa * (sa - TSE_R(2.0) * uc) - sb * (sb - TSE_R(2.0) * vc);
    const tse_real f2c = sa * (sa - TSE_R(2.0) * uc) + dn2 - L * L - gg * w2;
    const tse_real f1r = TSE_R(2.0) * (tse_fabs(sa) + tse_fabs(sb)) * rho + fpad;
    const tse_real f2r = TSE_R(2.0) * tse_fabs(sa) * rho + TSE_R(2.0) * dn * rho + rho * rho + fpad;
    const tse_real z0a = tse_fabs(y00 * f1c + y01 * f2c) + ay00 * f1r + ay01 * f2r;
    const tse_real z0b = tse_fabs(y10 * f1c + y11 * f2c) + ay10 * f1r + ay11 * f2r;

    /* Krawczyk: kappa = z0 + |Y| dM(r) r < r, with dM(r) how far M's entries move over the box. */
    const tse_real k10a = TSE_R(2.0) * tse_fabs(TSE_R(1.0) - gg), kgc = TSE_R(2.0) * tse_fabs(gg * c);
    const tse_real k11b = TSE_R(2.0) * tse_fabs(gg);
    const tse_real tiny = TSE_R(8.0) * TSE_REAL_EPS * (tse_fabs(sa) + tse_fabs(sb));
    /* Y M_c is the identity only up to rounding: that residue times the box, too. */
    const tse_real resid = TSE_R(16.0) * TSE_REAL_EPS * (ay00 + ay01 + ay10 + ay11) *
                           (tse_fabs(m00) + tse_fabs(m01) + tse_fabs(m10) + tse_fabs(m11));
    /* The box is chosen just wider than the residual's share, where kappa's quadratic part is
     * still small, and widened from kappa itself when that fails. */
    tse_real ra = TSE_R(1.05) * z0a + tiny, rb = TSE_R(1.05) * z0b + tiny;
    tse_real d00 = 0, d01 = 0, d10 = 0, d11 = 0;
    int ok = 0;
    for (int attempt = 0; attempt < 6 && !ok; ++attempt) {
        d00 = TSE_R(2.0) * (ra + rho);
        d01 = TSE_R(2.0) * (rb + rho);
        d10 = k10a * ra + kgc * rb + TSE_R(2.0) * rho;
        d11 = k11b * rb + kgc * ra;
        const tse_real rmax = ra > rb ? ra : rb;
        const tse_real ka = (z0a + (ay00 * d00 + ay01 * d10) * ra + (ay00 * d01 + ay01 * d11) * rb + resid * rmax) *
                            (TSE_R(1.0) + WIDEN);
        const tse_real kb = (z0b + (ay10 * d00 + ay11 * d10) * ra + (ay10 * d01 + ay11 * d11) * rb + resid * rmax) *
                            (TSE_R(1.0) + WIDEN);
        if (ka < ra && kb < rb) {
            ok = 1;
        } else {
            ra = TSE_R(1.25) * (ka > ra ? ka : ra);
            rb = TSE_R(1.25) * (kb > rb ? kb : rb);
        }
    }
    /* A box as wide as a tenth of the scissor says nothing useful even if it held. */
    if (!ok || !(ra < TSE_R(0.1) * L && rb < TSE_R(0.1) * L))
        return 0;
    box->r[0] = ra;
    box->r[1] = rb;

    const ci M00 = mk(m00, d00), M01 = mk(m01, d01), M10 = mk(m10, d10), M11 = mk(m11, d11);
    const ci D = sub(mul(M00, M11), mul(M01, M10));
    if (!(D.c - D.r > TSE_R(0.0)))
        return 0;

    /* The checks of kinematics.md over the box widened by the solver's accuracy, as tse_ik's
     * check_scissor states them. */
    const tse_real ca = ra + IK_ACCURACY, cb = rb + IK_ACCURACY;
    const tse_real e00 = TSE_R(2.0) * (ca + rho), e01 = TSE_R(2.0) * (cb + rho);
    const tse_real e10 = k10a * ca + kgc * cb + TSE_R(2.0) * rho, e11 = k11b * cb + kgc * ca;
    const ci W00 = mk(m00, e00), W01 = mk(m01, e01), W10 = mk(m10, e10), W11 = mk(m11, e11);
    const ci Dc = sub(mul(W00, W11), mul(W01, W10));
    const tse_real det_lo = Dc.c - Dc.r;
    const tse_real w2r = tse_fabs(TSE_R(2.0) * sa + TSE_R(2.0) * c * sb) * ca +
                         tse_fabs(TSE_R(2.0) * sb + TSE_R(2.0) * c * sa) * cb + ca * ca + cb * cb +
                         TSE_R(2.0) * tse_fabs(c) * ca * cb + TSE_R(8.0) * TSE_REAL_EPS * (sa * sa + sb * sb);
    const tse_real n1 = sup(W00) * sup(W00) + sup(W01) * sup(W01);
    const tse_real n2 = sup(W10) * sup(W10) + sup(W11) * sup(W11);
    const tse_real mu_min = g->p.mu_min;
    /* tse_ik's type-1 check also asks mu_guard / (mu n_min) of room for its slides' rounding
     * (scissor_core.h, with n_min over M / 2's rows, a quarter of these): proven at the box's
     * least mu and shortest row. */
    const tse_real r1lo = mig(W00) * mig(W00) + mig(W01) * mig(W01);
    const tse_real r2lo = mig(W10) * mig(W10) + mig(W11) * mig(W11);
    const tse_real row_lo = (r1lo < r2lo ? r1lo : r2lo) * (TSE_R(1.0) - WIDEN);
    const tse_real mu_lo = det_lo / tse_sqrt(n1 * n2) * (TSE_R(1.0) - WIDEN);
    /* In the contract's order, as tse_ik names a failing pose. */
    *failed = !(d[2] - rho > TSE_R(0.0))                                                   ? TSE_BELOW
              : !(w2 - w2r >= g->w_lo * g->w_lo && w2 + w2r <= g->w_hi * g->w_hi)         ? TSE_ALPHA
              : !(sa - ca >= g->p.s_min && sa + ca <= g->p.s_max && sb - cb >= g->p.s_min &&
                  sb + cb <= g->p.s_max)                                                  ? TSE_STROKE
              : !(det_lo > TSE_R(0.0) && det_lo * det_lo >= mu_min * mu_min * n1 * n2 * (TSE_R(1.0) + WIDEN) &&
                  mu_lo * (mu_lo - mu_min) * row_lo >= TSE_R(4.0) * g->mu_guard * (TSE_R(1.0) + WIDEN))
                  ? TSE_SINGULAR
                  : TSE_OK;

    /* First derivatives: M q' = -2 (G1, G2), G1 = (s_B b - s_A a).C', G2 = (d - s_A a).C'. */
    const tse_real *d1 = jm->d1, *d2 = jm->d2;
    const ci Sa = mk(sa, ra), Sb = mk(sb, rb);
    const ci U1 = mk(d1[0] * f->a[0] + d1[1] * f->a[1], jm->rho1);
    const ci V1 = mk(d1[0] * f->b[0] + d1[1] * f->b[1], jm->rho1);
    const tse_real n_d1 = norm3(d1), n_d2 = norm3(d2);
    const ci DC1 = mk(dot3(d, d1), dn * jm->rho1 + rho * n_d1 + rho * jm->rho1);
    const ci SaU1 = mul(Sa, U1);
    const ci G1 = sub(mul(Sb, V1), SaU1);
    const ci G2 = sub(DC1, SaU1);
    const ci Qa = divp(scale(TSE_R(-2.0), sub(mul(M11, G1), mul(M01, G2))), D);
    const ci Qb = divp(scale(TSE_R(-2.0), sub(mul(M00, G2), mul(M10, G1))), D);

    /* Second derivatives: M q'' = (R1, R2), differentiating the first-derivative equations. */
    const ci U2 = mk(d2[0] * f->a[0] + d2[1] * f->a[1], jm->rho2);
    const ci V2 = mk(d2[0] * f->b[0] + d2[1] * f->b[1], jm->rho2);
    const ci DC2 = mk(dot3(d, d2), dn * jm->rho2 + rho * n_d2 + rho * jm->rho2);
    const ci C1C1 = mk(dot3(d1, d1), TSE_R(2.0) * n_d1 * jm->rho1 + jm->rho1 * jm->rho1);
    const ci Qa2 = sqr(Qa), Qb2 = sqr(Qb);
    const ci common = sub(scale(TSE_R(2.0), Qa2), add(scale(TSE_R(4.0), mul(Qa, U1)), scale(TSE_R(2.0), mul(Sa, U2))));
    const ci R1 = scale(TSE_R(-1.0), add(common, sub(scale(TSE_R(4.0), mul(Qb, V1)),
                                                     sub(scale(TSE_R(2.0), Qb2), scale(TSE_R(2.0), mul(Sb, V2))))));
    const ci quad = add(add(Qa2, Qb2), scale(TSE_R(2.0) * c, mul(Qa, Qb)));
    const ci R2 = scale(TSE_R(-1.0), add(common, sub(scale(TSE_R(2.0), add(C1C1, DC2)), scale(TSE_R(2.0) * gg, quad))));
    const ci Pa = divp(sub(mul(M11, R1), mul(M01, R2)), D);
    const ci Pb = divp(sub(mul(M00, R2), mul(M10, R1)), D);

    /* Midpoint arithmetic is the point formula at the centre: the derivatives there. */
    dq_c[0] = Qa.c;
    dq_c[1] = Qb.c;
    ddq_c[0] = Pa.c;
    ddq_c[1] = Pb.c;
    dq[0] = sup(Qa);
    dq[1] = sup(Qb);
    ddq[0] = sup(Pa);
    ddq[1] = sup(Pb);
    return isfinite(dq[0] + dq[1] + ddq[0] + ddq[1]);
}

/* How far the unit row along (g, s (axis_k . (rc x g))_k) of the type-2 matrix can move over the
 * piece.  A row x moved by at most delta |x| (delta < 1) turns by at most asin(delta), and its
 * unit vector by a chord shorter than that arc: below delta / sqrt(1 - delta^2). */
static tse_real row_change(const tse_real axes[3][3], const tse_real d_axis[3], tse_real s,
                           const tse_real rc[3], tse_real d_rc, const tse_real gr[3], tse_real d_g)
{
    tse_real w[3];
    cross3(rc, gr, w);
    const tse_real ng = norm3(gr);
    tse_real n = ng * ng;
    for (int k = 0; k < 3; ++k) {
        const tse_real t = s * dot3(axes[k], w);
        n += t * t;
    }
    n = tse_sqrt(n);
    if (!(n > TSE_R(0.0)))
        return (tse_real)INFINITY;
    const tse_real d_w = d_rc * ng + norm3(rc) * d_g + d_rc * d_g;
    const tse_real w_max = norm3(w) + d_w;
    tse_real change = d_g;
    for (int k = 0; k < 3; ++k)
        change += s * (d_axis[k] * w_max + d_w);
    const tse_real delta = change / n;
    if (!(delta < TSE_R(0.5)))
        return (tse_real)INFINITY;
    return delta / tse_sqrt(TSE_R(1.0) - delta * delta);
}

int tse_ik_enclose(const tse_geometry *g, const tse_piece *piece, const tse_real pose[6],
                   const tse_ik_result *centre, tse_enclosure *out)
{
    out->enclosed = 0;
    out->proven = 0;
    out->scissor = 1;
    out->status = TSE_INVALID;
    if (centre->status != TSE_OK)
        return 0;
    const tse_real r_top = g->r_top;
    const tse_real n_lin = norm3(piece->lin), n_om = norm3(piece->omega), h = piece->half;
    if (!isfinite(n_lin + n_om + h + piece->pad) || !(h >= TSE_R(0.0)))
        return 0;
    const tse_real widen = TSE_R(1.0) + TSE_R(16.0) * TSE_REAL_EPS;

    int proven_all = 1;
    scissor_box boxes[3];
    tse_real rcs[3][3];
    for (int i = 0; i < 3; ++i) {
        joint_motion jm;
        tse_real *rc = rcs[i];
        for (int k = 0; k < 3; ++k)
            rc[k] = centre->C[i][k] - pose[k];
        const tse_real n_rc = norm3(rc);
        jm.rho = (n_lin + n_om * n_rc) * h * widen + piece->pad;
        tse_real wr[3];
        cross3(piece->omega, rc, wr);
        for (int k = 0; k < 3; ++k)
            jm.d1[k] = piece->lin[k] + wr[k];
        cross3(piece->omega, wr, jm.d2);
        jm.rho1 = n_om * n_om * (n_rc * h + piece->pad) * widen;
        jm.rho2 = n_om * n_om * n_om * (n_rc * h + piece->pad) * widen;
        tse_status failed = TSE_OK;
        tse_real dq[2], ddq[2], dq_c[2], ddq_c[2];
        if (!enclose_scissor(g, i, centre->C[i], &centre->q[2 * i], &jm, &boxes[i], &failed, dq, ddq, dq_c,
                             ddq_c)) {
            out->scissor = i + 1;
            out->status = TSE_SINGULAR;
            return 0;
        }
        for (int k = 0; k < 2; ++k) {
            const int j = 2 * i + k;
            out->q_lo[j] = centre->q[j] - boxes[i].r[k];
            out->q_hi[j] = centre->q[j] + boxes[i].r[k];
            out->dq[j] = dq[k];
            out->ddq[j] = ddq[k];
            out->dq_c[j] = dq_c[k];
            out->ddq_c[j] = ddq_c[k];
        }
        if (failed != TSE_OK && proven_all) {
            proven_all = 0;
            out->scissor = i + 1;
            out->status = failed;
        }
    }
    out->enclosed = 1;
    if (!proven_all)
        return 0;

    /* Type 2 (tse_ik's nu, rot_scale 1 / r_top): the centre's ratio less every row's change.  The
     * axes about which roll, pitch and yaw turn (tse_plate_frame): R e_x, (-sin yaw, cos yaw, 0)
     * and e_z.  Over the piece the plate turns by phi at most; R e_x then moves by phi, and yaw by
     * at most phi / cos(pitch)'s smallest value, since cos(pitch) is R e_x's horizontal length. */
    const tse_real cy = tse_cos(pose[TSE_YAW]), sy = tse_sin(pose[TSE_YAW]);
    const tse_real cp = tse_cos(pose[TSE_PITCH]), sp = tse_sin(pose[TSE_PITCH]);
    const tse_real axes[3][3] = {{cy * cp, sy * cp, -sp}, {-sy, cy, TSE_R(0.0)}, {TSE_R(0.0), TSE_R(0.0), TSE_R(1.0)}};
    const tse_real phi = (n_om * h + piece->pad / r_top) * widen;
    const tse_real cp_lo = tse_fabs(cp) - phi;
    out->status = TSE_DEGENERATE; /* until the type-2 bound holds */
    if (!(cp_lo > TSE_R(0.0))) {
        out->scissor = 1;
        return 0;
    }
    const tse_real d_axis[3] = {phi, phi / cp_lo, TSE_R(0.0)};
    const tse_real s = g->inv_r_top;
    tse_real loss = TSE_R(0.0);
    for (int i = 0; i < 3; ++i) {
        const tse_scissor_frame *f = &g->sc[i];
        const tse_real sa = centre->q[2 * i], sb = centre->q[2 * i + 1];
        const tse_real *d = boxes[i].d;
        /* Halved gradients of F1 and F2 with respect to the ball joint, as tse_type2_margin. */
        const tse_real g1[3] = {sb * f->b[0] - sa * f->a[0], sb * f->b[1] - sa * f->a[1], TSE_R(0.0)};
        const tse_real g2[3] = {d[0] - sa * f->a[0], d[1] - sa * f->a[1], d[2]};
        const tse_real ra = boxes[i].r[0], rb = boxes[i].r[1];
        const tse_real d_rc = norm3(rcs[i]) * phi;
        loss += row_change(axes, d_axis, s, rcs[i], d_rc, g1, ra + rb + TSE_R(2.0) * IK_ACCURACY);
        loss += row_change(axes, d_axis, s, rcs[i], d_rc, g2, boxes[i].rho + ra + IK_ACCURACY);
    }
    const tse_real nu_lo = centre->nu * (TSE_R(1.0) - TSE_R(64.0) * TSE_REAL_EPS) - loss * widen -
                           TSE_R(64.0) * TSE_REAL_EPS;
    if (!(nu_lo >= g->p.nu_min)) {
        out->scissor = 1;
        return 0;
    }
    out->proven = 1;
    out->scissor = 0;
    out->status = TSE_OK;
    return 1;
}
