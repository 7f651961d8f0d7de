/* tse_ik_enclose (tse/enclose.h) against the long-double oracle sampled densely over each piece:
 * every sampled pose's exact branch solution lies in the box; a proven piece has no sampled pose
 * the oracle refuses; the bounds on dq/du and d2q/du2 hold against the oracle's finite
 * differences, and the centre's derivatives match them.  Pieces are random, many of them
 * straddling a limit (the workspace boundary found by bisection along a ray from home), and the
 * designs include ones where the stroke, type-1 and type-2 margins bind. */
#include <stdlib.h>

#include "test_common.h"
#include "tse/enclose.h"

enum { SAMPLES = 48, PIECES = 260 };

typedef struct {
    long pieces, enclosed, proven, grazing, grazing_proven, grazing_refused, samples;
} counts;

/* Pose at offset du along the piece: the position on its line, the orientation turned about the
 * world axis omega by |omega| du from the centre's (long double throughout). */
static void piece_pose(const orc_real centre[6], const orc_real lin[3], const orc_real om[3], orc_real du,
                       orc_real out[6])
{
    orc_real Rc[3][3], K[3][3], R[3][3];
    orc_rotation(centre[3], centre[4], centre[5], Rc);
    const orc_real n = sqrtl(om[0] * om[0] + om[1] * om[1] + om[2] * om[2]);
    const orc_real th = n * du;
    orc_real k[3] = {0, 0, 0};
    if (n > 0)
        for (int j = 0; j < 3; ++j)
            k[j] = om[j] / n;
    /* Rodrigues: I + sin th [k] + (1 - cos th) [k]^2 */
    const orc_real kx[3][3] = {{0, -k[2], k[1]}, {k[2], 0, -k[0]}, {-k[1], k[0], 0}};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            orc_real kk = 0;
            for (int m = 0; m < 3; ++m)
                kk += kx[i][m] * kx[m][j];
            K[i][j] = (i == j ? 1.0L : 0.0L) + sinl(th) * kx[i][j] + (1.0L - cosl(th)) * kk;
        }
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            R[i][j] = 0;
            for (int m = 0; m < 3; ++m)
                R[i][j] += K[i][m] * Rc[m][j];
        }
    for (int j = 0; j < 3; ++j)
        out[j] = centre[j] + lin[j] * du;
    orc_rpy(R, &out[3], &out[4], &out[5]);
}

static void exact_q(const orc_geom *og, const orc_real pose[6], const orc_real prefer[6], orc_result *o)
{
    const orc_tol tol = test_orc_tol();
    orc_ik(og, pose, prefer, &tol, o);
}

/* The largest step t along dir from home that tse_ik still accepts (bisection, 40 halvings). */
static double boundary(const tse_geometry *g, const double dir[6])
{
    double lo = 0.0, hi = 1.0;
    for (int it = 0; it < 40; ++it) {
        const double mid = 0.5 * (lo + hi);
        tse_real p[6];
        for (int k = 0; k < 6; ++k)
            p[k] = (tse_real)(g->home_pose[k] + mid * dir[k]);
        tse_ik_result r;
        if (tse_ik(g, p, NULL, &r) == TSE_OK)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

static void run_design(const tse_params *p, uint64_t seed, counts *c)
{
    tse_geometry g;
    orc_geom og;
    test_geometries(p, &g, &og);
    uint64_t rng = seed;
    for (int n = 0; n < PIECES; ++n) {
        /* A centre in or near the workspace; half the pieces pushed onto its boundary. */
        double dir[6] = {rng_range(&rng, -0.25, 0.25), rng_range(&rng, -0.25, 0.25), rng_range(&rng, -0.6, 0.6),
                         rng_range(&rng, -0.3, 0.3),   rng_range(&rng, -0.3, 0.3),   rng_range(&rng, -0.5, 0.5)};
        double t = rng_range(&rng, 0.0, 0.8);
        const int grazing = n % 2 == 0;
        if (grazing)
            t = boundary(&g, dir) * (1.0 + rng_range(&rng, -0.01, 0.003));
        tse_real pose[6];
        for (int k = 0; k < 6; ++k)
            pose[k] = (tse_real)(g.home_pose[k] + t * dir[k]);
        tse_ik_result centre;
        if (tse_ik(&g, pose, NULL, &centre) != TSE_OK)
            continue;
        tse_piece piece;
        const double speed = rng_range(&rng, 0.0, 1.0), turn = rng_range(&rng, 0.0, 0.8);
        double l[3], w[3], nl = 0, nw = 0;
        for (int k = 0; k < 3; ++k) {
            l[k] = rng_range(&rng, -1, 1);
            w[k] = rng_range(&rng, -1, 1);
            nl += l[k] * l[k];
            nw += w[k] * w[k];
        }
        for (int k = 0; k < 3; ++k) {
            piece.lin[k] = (tse_real)(speed * l[k] / sqrt(nl));
            piece.omega[k] = (tse_real)(turn * w[k] / sqrt(nw));
        }
        piece.half = (tse_real)exp(rng_range(&rng, log(1e-5), log(0.05)));
        /* The centre's ball joints are the solver's, rounded: the caller's pad (fw/validate.c's). */
        piece.pad = (tse_real)(64.0 * TSE_REAL_EPS * (fabs(pose[0]) + fabs(pose[1]) + fabs(pose[2]) + g.r_top));
        tse_enclosure e;
        const int proven = tse_ik_enclose(&g, &piece, pose, &centre, &e);
        ++c->pieces;
        c->grazing += grazing;
        c->enclosed += e.enclosed;
        c->proven += proven;
        c->grazing_proven += proven && grazing;

        orc_real pc[6], lin[3], om[3], prefer[6];
        for (int k = 0; k < 6; ++k) {
            pc[k] = (orc_real)pose[k];
            prefer[k] = (orc_real)centre.q[k];
        }
        for (int k = 0; k < 3; ++k) {
            lin[k] = (orc_real)piece.lin[k];
            om[k] = (orc_real)piece.omega[k];
        }
        const orc_real h = (orc_real)piece.half;
        int refused = 0;
        for (int s = 0; s <= SAMPLES; ++s) {
            const orc_real du = -h + 2.0L * h * (orc_real)s / SAMPLES;
            orc_real ps[6];
            orc_result o;
            piece_pose(pc, lin, om, du, ps);
            exact_q(&og, ps, prefer, &o);
            ++c->samples;
            if (o.status != TSE_OK)
                refused = 1;
            if (proven && o.status != TSE_OK && !o.ambiguous)
                fail_msg("piece %d proven, but the oracle refuses its pose at du %Lg: status %d scissor %d", n, du,
                         o.status, o.scissor);
            if (!e.enclosed)
                continue;
            for (int k = 0; k < 6; ++k) {
                if (isnan((double)o.q[k]))
                    continue;
                if (!(o.q[k] >= e.q_lo[k] - TOL_Q && o.q[k] <= e.q_hi[k] + TOL_Q))
                    fail_msg("piece %d: slide %d = %.12Lg at du %Lg outside the box [%.12g, %.12g]", n, k, o.q[k], du,
                             (double)e.q_lo[k], (double)e.q_hi[k]);
            }
            /* Derivatives by central differences of the exact solution (long double). */
            if (s % 8 != 0 || s == 0 || s == SAMPLES || o.status == TSE_UNREACHABLE)
                continue;
            /* within the piece, and wide enough that long double's rounding stays far below */
            const orc_real fd = h / 8 < 1e-5L ? h / 8 : 1e-5L;
            orc_real pm[6], pp[6];
            orc_result om1, op1;
            piece_pose(pc, lin, om, du - fd, pm);
            piece_pose(pc, lin, om, du + fd, pp);
            exact_q(&og, pm, o.q, &om1);
            exact_q(&og, pp, o.q, &op1);
            for (int k = 0; k < 6; ++k) {
                const orc_real d1 = (op1.q[k] - om1.q[k]) / (2.0L * fd);
                const orc_real d2 = (op1.q[k] - 2.0L * o.q[k] + om1.q[k]) / (fd * fd);
                if (isnan((double)d1))
                    continue;
                if (fabsl(d1) > (orc_real)e.dq[k] * (1.0L + 1e-6L) + 1e-9L)
                    fail_msg("piece %d: |dq%d/du| = %Lg at du %Lg above its bound %g", n, k, fabsl(d1), du,
                             (double)e.dq[k]);
                /* the second difference's own error: fd^2 q'''' and 4 eps_ld q / fd^2 */
                if (fabsl(d2) > (orc_real)e.ddq[k] * (1.0L + 1e-4L) + 1e-4L)
                    fail_msg("piece %d: |d2q%d/du2| = %Lg at du %Lg above its bound %g", n, k, fabsl(d2), du,
                             (double)e.ddq[k]);
                if (s == SAMPLES / 2) {
                    /* the differences' own error, fd^2 q''' / 6 and fd^2 q'''' / 12, and float's */
                    const double tol1 = IS_FLOAT ? 2e-3 : 1e-6, tol2 = IS_FLOAT ? 2e-2 : 1e-4;
                    if (fabs((double)d1 - (double)e.dq_c[k]) > tol1 * (1.0 + fabs((double)d1)))
                        fail_msg("piece %d: dq%d/du at the centre %g, the oracle's %Lg", n, k, (double)e.dq_c[k], d1);
                    if (fabs((double)d2 - (double)e.ddq_c[k]) > tol2 * (1.0 + fabs((double)d2)))
                        fail_msg("piece %d: d2q%d/du2 at the centre %g, the oracle's %Lg", n, k, (double)e.ddq_c[k],
                                 d2);
                }
            }
        }
        c->grazing_refused += grazing && refused;
    }
}

static void test_random_pieces(void **state)
{
    (void)state;
    counts c = {0};
    tse_params p;
    tse_params_default(&p);
    run_design(&p, 1, &c);
    /* The stroke binds before the stops. */
    tse_params_default(&p);
    p.s_max = (tse_real)0.55;
    run_design(&p, 2, &c);
    /* The type-1 margin binds. */
    tse_params_default(&p);
    p.mu_min = (tse_real)0.6;
    run_design(&p, 3, &c);
    /* The type-2 margin binds. */
    tse_params_default(&p);
    p.nu_min = (tse_real)0.5;
    run_design(&p, 4, &c);
    printf("enclose (%s): %ld pieces, %ld enclosed, %ld proven; %ld grazing a limit, %ld of them proven, "
           "%ld with a pose the oracle refuses; %ld poses sampled\n",
           TSE_REAL_NAME, c.pieces, c.enclosed, c.proven, c.grazing, c.grazing_proven, c.grazing_refused, c.samples);
    /* Not vacuous: most pieces proven, and pieces on the boundary both proven and refused. */
    assert_true(c.proven > c.pieces / 3);
    assert_true(c.grazing_proven > 20);
    assert_true(c.grazing_refused > 20);
}

/* A piece of no length at a pose: the box is the solver's point, a rounding pad wide, and the bounds
 * are the exact derivatives there. */
static void test_point_piece(void **state)
{
    (void)state;
    tse_geometry g;
    orc_geom og;
    test_default_geometries(&g, &og);
    tse_ik_result centre;
    assert_int_equal(tse_ik(&g, g.home_pose, NULL, &centre), TSE_OK);
    const tse_piece piece = {{TSE_R(0.0), TSE_R(0.0), TSE_R(0.1)}, {TSE_R(0.0), TSE_R(0.0), TSE_R(0.0)}, TSE_R(0.0),
                             TSE_R(0.0)};
    tse_enclosure e;
    assert_true(tse_ik_enclose(&g, &piece, g.home_pose, &centre, &e));
    for (int k = 0; k < 6; ++k) {
        /* the residual's rounding pad, 16 eps of terms of a few m^2, over |M| of a metre or two */
        assert_true(e.q_hi[k] - e.q_lo[k] < 512 * TSE_REAL_EPS * (double)g.p.L);
        assert_true(e.dq[k] >= fabs((double)e.dq_c[k]));
        assert_true(e.dq[k] - fabs((double)e.dq_c[k]) < (IS_FLOAT ? 1e-3 : 1e-9) * fabs((double)e.dq_c[k]) + 1e-12);
    }
    /* On the axis, moving straight up: every slide moves alike, at ds/dz of the closed form (by
     * hand from kinematics.md's vertical solution, differenced in long double). */
    const orc_real z = (orc_real)g.home_pose[TSE_Z], dz = 1e-6L;
    const orc_real ds = (orc_vertical_slide(&og, z + dz) - orc_vertical_slide(&og, z - dz)) / (2 * dz);
    for (int k = 0; k < 6; ++k)
        if (fabs((double)e.dq_c[k] - 0.1 * (double)ds) > (IS_FLOAT ? 1e-4 : 1e-9))
            fail_msg("slide %d: dq/du %g, by the closed form %Lg", k, (double)e.dq_c[k], 0.1L * ds);
}

/* Refusals: a centre the solver refused, and a piece so long that its box says nothing. */
static void test_refusals(void **state)
{
    (void)state;
    tse_geometry g;
    orc_geom og;
    test_default_geometries(&g, &og);
    tse_ik_result centre;
    assert_int_equal(tse_ik(&g, g.home_pose, NULL, &centre), TSE_OK);
    tse_piece piece = {{TSE_R(0.0), TSE_R(0.0), TSE_R(1.0)}, {TSE_R(0.0), TSE_R(0.0), TSE_R(0.0)}, TSE_R(0.5),
                       TSE_R(0.0)};
    tse_enclosure e;
    assert_false(tse_ik_enclose(&g, &piece, g.home_pose, &centre, &e));
    assert_false(e.proven);
    centre.status = TSE_ALPHA;
    piece.half = TSE_R(0.0);
    assert_false(tse_ik_enclose(&g, &piece, g.home_pose, &centre, &e));
    assert_false(e.enclosed);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_point_piece),
        cmocka_unit_test(test_refusals),
        cmocka_unit_test(test_random_pieces),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
