/* The full inverse kinematics in fixed point: the ball joints from the pose, each scissor's
 * solution (fx_scissor.h), and the contract's checks in its order (kinematics.md), as tse_ik of
 * the float and double builds does them (kinematics/src/ik.c says why each is done its way). */
#include "fx_math.h"
#include "fx_scissor.h"
#include "tse/ik_fixed.h"

#define FX_HALF_SQRT3 929887697 /* sqrt(3)/2 in Q30 */

/* What the ball joints and the type-2 check need of the orientation (Q30). */
typedef struct {
    int32_t rho[3][3]; /* R e_r_i */
    int32_t N[3];      /* R e_z */
    int32_t sy, cy, cp;
} pose_frame;

static int32_t mul30(int32_t a, int32_t b)
{
    return (int32_t)fx_shr((int64_t)a * b, 30);
}

static void pose_frame_of(const int32_t pose[6], pose_frame *f)
{
    int32_t sr, cr, sp, cp, sy, cy;
    tse_fx_sincos(pose[3], &sr, &cr);
    tse_fx_sincos(pose[4], &sp, &cp);
    tse_fx_sincos(pose[5], &sy, &cy);
    const int32_t cysp = mul30(cy, sp), sysp = mul30(sy, sp);
    const int32_t col0[3] = {mul30(cy, cp), mul30(sy, cp), -sp};
    const int32_t col1[3] = {mul30(cysp, sr) - mul30(sy, cr), mul30(sysp, sr) + mul30(cy, cr), mul30(cp, sr)};
    f->N[0] = mul30(cysp, cr) + mul30(sy, sr);
    f->N[1] = mul30(sysp, cr) - mul30(cy, sr);
    f->N[2] = mul30(cp, cr);
    for (int k = 0; k < 3; ++k) {
        const int32_t m = -(col0[k] / 2), t = mul30(FX_HALF_SQRT3, col1[k]);
        f->rho[0][k] = col0[k];
        f->rho[1][k] = m + t;
        f->rho[2][k] = m - t;
    }
    f->sy = sy;
    f->cy = cy;
    f->cp = cp;
}

/* Q24 x Q30 -> Q24 of a length within int32 (every length of a solution: below 128 m). */
static int32_t lu(int32_t len, int32_t unit)
{
    return (int32_t)fx_shr((int64_t)len * unit, 30);
}

/* The normal n_i = g1 x g2 of scissor i's two constraint gradients and the product of its two
 * rows' squared norms in dF/dp (ik.c, type2_normal, in the same form).  Its slides, ball joint and
 * gradients are all below 32 m, and so every row entry is (below 64 m: int32 in Q24). */
static fx_scaled type2_normal(const tse_fx_geometry *g, const pose_frame *f, int i, const fx_local *loc,
                              int32_t s_a, int32_t s_b, int32_t n[3])
{
    const tse_fx_scissor_frame *sf = &g->sc[i];
    const int32_t *rho = f->rho[i];
    static const int32_t SB[3] = {0, FX_HALF_SQRT3, -FX_HALF_SQRT3};
    const int32_t sb = SB[i];
    const int32_t aa[2] = {lu(s_a, sf->a[0]), lu(s_a, sf->a[1])};
    const int32_t g1[2] = {lu(s_b, sf->b[0]) - aa[0], lu(s_b, sf->b[1]) - aa[1]};
    const int32_t g2[3] = {loc->d[0] - aa[0], loc->d[1] - aa[1], loc->d[2]};
    const int32_t h[3] = {mul30(f->cy, rho[2]), mul30(f->sy, rho[2]), -(mul30(f->sy, rho[1]) + mul30(f->cy, rho[0]))};
    const int32_t r1 = lu(lu(g1[0], f->N[0]) + lu(g1[1], f->N[1]), sb);
    const int32_t p1 = lu(g1[0], h[0]) + lu(g1[1], h[1]);
    const int32_t y1 = lu(g1[1], rho[0]) - lu(g1[0], rho[1]);
    const int32_t r2 = lu(lu(g2[0], f->N[0]) + lu(g2[1], f->N[1]) + lu(g2[2], f->N[2]), sb);
    const int32_t p2 = lu(g2[0], h[0]) + lu(g2[1], h[1]) + lu(g2[2], h[2]);
    const int32_t y2 = lu(g2[1], rho[0]) - lu(g2[0], rho[1]);
#define SQ(x) ((int64_t)(x) * (x))
    const int64_t nn1 = SQ(g1[0]) + SQ(g1[1]) + SQ(r1) + SQ(p1) + SQ(y1);
    const int64_t nn2 = SQ(g2[0]) + SQ(g2[1]) + SQ(g2[2]) + SQ(r2) + SQ(p2) + SQ(y2);
#undef SQ
    /* n in Q20 m^2 (below 2048 m^2: int32) */
    n[0] = (int32_t)(((int64_t)g2[2] * g1[1]) >> 28);
    n[1] = (int32_t)-(((int64_t)g2[2] * g1[0]) >> 28);
    n[2] = (int32_t)(((int64_t)g1[0] * g2[1] - (int64_t)g1[1] * g2[0]) >> 28);
    return fx_scaled_mul(fx_scaled_of(nn1, 48), fx_scaled_of(nn2, 48));
}

static int64_t dot_e(const int32_t n[3], const pose_frame *f, int i, int j)
{
    int64_t s = 0;
    for (int k = 0; k < 3; ++k)
        s += (int64_t)n[k] * (f->rho[i][k] - f->rho[j][k]);
    return s >> 30; /* Q20 m^2 */
}

/* The Hadamard ratio from the three normals and the rows' norms (ik.c, type2_ratio), Q30. */
static int32_t type2_ratio(const pose_frame *f, const int32_t n[3][3], const fx_scaled nn[3])
{
    if (nn[0].m <= 0 || nn[1].m <= 0 || nn[2].m <= 0)
        return 0;
    const fx_scaled t1 = fx_scaled_mul(fx_scaled_mul(fx_scaled_of(dot_e(n[0], f, 0, 1), 20),
                                                     fx_scaled_of(dot_e(n[1], f, 1, 2), 20)),
                                       fx_scaled_of(dot_e(n[2], f, 0, 2), 20));
    const fx_scaled t2 = fx_scaled_mul(fx_scaled_mul(fx_scaled_of(dot_e(n[1], f, 0, 1), 20),
                                                     fx_scaled_of(dot_e(n[0], f, 0, 2), 20)),
                                       fx_scaled_of(dot_e(n[2], f, 1, 2), 20));
    fx_scaled det = fx_scaled_mul(fx_scaled_sub(t1, t2), fx_scaled_of(f->cp, 30));
    if (det.m < 0)
        det.m = -det.m;
    const fx_scaled den = fx_scaled_sqrt(fx_scaled_mul(fx_scaled_mul(nn[0], nn[1]), nn[2]));
    if (den.m <= 0)
        return 0;
    return fx_scaled_div(det, den, 30);
}

static tse_status check_scissor(const tse_fx_geometry *g, const int64_t C[3], const fx_sol *s)
{
    if (!(C[2] > 0))
        return TSE_BELOW;
    if (!(s->w2 >= g->w_lo2 && s->w2 <= g->w_hi2))
        return TSE_ALPHA;
    if (!(s->s_a >= g->p.s_min && s->s_a <= g->p.s_max && s->s_b >= g->p.s_min && s->s_b <= g->p.s_max))
        return TSE_STROKE;
    if (!fx_mu_clear(g, s))
        return TSE_SINGULAR;
    return TSE_OK;
}

static int32_t clamp32(int64_t x)
{
    return x > INT32_MAX ? INT32_MAX : x < INT32_MIN + 1 ? INT32_MIN + 1 : (int32_t)x;
}

tse_status tse_fx_ik(const tse_fx_geometry *g, const int32_t pose[6], const int32_t *seed_q,
                     tse_fx_ik_result *out)
{
    out->status = TSE_OK;
    out->scissor = 0;
    out->nu = TSE_FX_NONE;
    out->iterations = 0;
    out->fallbacks = 0;
    pose_frame frame;
    pose_frame_of(pose, &frame);
    int64_t C[3][3]; /* Q28 */
    for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k) {
            C[i][k] = (int64_t)pose[k] * 16 + (((int64_t)g->r_top28 * frame.rho[i][k]) >> 30);
            out->C[i][k] = clamp32((C[i][k] + 8) >> 4);
        }
    for (int k = 0; k < 6; ++k)
        out->q[k] = TSE_FX_NONE;
    for (int i = 0; i < 3; ++i)
        out->mu[i] = TSE_FX_NONE;
    /* A seed beyond the format's room is malformed: `invalid`, at scissor 1 as a non-finite one. */
    if (seed_q)
        for (int k = 0; k < 6; ++k)
            if (seed_q[k] > g->s_box || seed_q[k] < -g->s_box) {
                out->status = TSE_INVALID;
                out->scissor = 1;
                return TSE_INVALID;
            }

    tse_status first = TSE_OK;
    int first_scissor = 0;
    int32_t n[3][3];
    fx_scaled nn[3];
    fx_local loc[3];
    for (int i = 0; i < 3; ++i) {
        fx_localize(g, i, C[i], &loc[i]);
        fx_sol sol;
        const int32_t sa = seed_q ? seed_q[2 * i] : g->home_s, sb = seed_q ? seed_q[2 * i + 1] : g->home_s;
        tse_status st = fx_scissor_solve(g, &loc[i], sa, sb, &sol);
        out->iterations += sol.iterations;
        out->fallbacks += sol.fallback;
        if (st == TSE_OK) {
            out->q[2 * i] = sol.s_a;
            out->q[2 * i + 1] = sol.s_b;
            out->mu[i] = sol.mu;
            if (sol.fallback)
                st = check_scissor(g, C[i], &sol);
            else if (!(C[i][2] > 0))
                st = TSE_BELOW;
            else if (!fx_mu_clear(g, &sol))
                st = TSE_SINGULAR;
            if (st == TSE_OK)
                nn[i] = type2_normal(g, &frame, i, &loc[i], sol.s_a, sol.s_b, n[i]);
        }
        if (st != TSE_OK && first == TSE_OK) {
            first = st;
            first_scissor = i + 1;
        }
    }
    if (first != TSE_OK) {
        out->status = first;
        out->scissor = first_scissor;
        return first;
    }
    out->nu = type2_ratio(&frame, (const int32_t(*)[3])n, nn);
    if (!(out->nu >= g->p.nu_min)) {
        /* The float build names the row of dF/dp nearest the others' span; here scissor 1
         * (docs/kinematics.md, "The fixed-point build"). */
        out->status = TSE_DEGENERATE;
        out->scissor = 1;
        return TSE_DEGENERATE;
    }
    return TSE_OK;
}
