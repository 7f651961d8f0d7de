/* The fixed-point inverse kinematics (tse/ik_fixed.h) against the double build and the independent
 * long-double oracle (kinematics.md; docs/kinematics.md, "The fixed-point build"):
 *  - its integer sine, cosine and square root against the C library and exact integer bounds;
 *  - the worked values;
 *  - over the oracle sets the float build is tested on (test_oracle.c: the workspace and wide
 *    poses from home, warm-started trajectories, other designs), slides within 1 um of the double
 *    solution wherever the oracle's mu >= 0.1, and the double build's status (and scissor) on
 *    every pose the oracle finds clear of its "too close to call" bands;
 *  - the format's edges: positions at the ends of int32, angles that wrap, seeds beyond the room.
 * This file is double (tse_kin_d); expectations come from the double build, the oracle and hand
 * algebra, never from the fixed code. */
#include "test_common.h"
#include "tse/ik_fixed.h"

_Static_assert(sizeof(tse_real) == sizeof(double), "test_ik_fixed.c must be built as double");

static const double PI = 3.14159265358979323846;
#define TOL_FX_Q 1e-6 /* the goal: within 1 um of the double solution where mu >= 0.1 */

static int32_t to_len(double x)
{
    return (int32_t)llround(x * TSE_FX_M);
}
static int32_t to_ang(double x)
{
    return (int32_t)llround(x * TSE_FX_RAD);
}
static int32_t to_one(double x)
{
    return (int32_t)llround(x * TSE_FX_ONE);
}
static double from_len(int32_t x)
{
    return (double)x / TSE_FX_M;
}

/* The pose in the fixed formats, and the same numbers back in double (exact). */
static void pose_to_fx(const double in[6], int32_t fx[6], double back[6])
{
    for (int k = 0; k < 6; ++k) {
        fx[k] = k < 3 ? to_len(in[k]) : to_ang(in[k]);
        back[k] = k < 3 ? (double)fx[k] / TSE_FX_M : (double)fx[k] / TSE_FX_RAD;
    }
}

static void params_to_fx(const tse_params *p, tse_fx_params *f)
{
    f->L = to_len(p->L);
    f->k1 = to_one(p->k1);
    f->eta = to_ang(p->eta);
    f->k3 = to_one(p->k3);
    f->k4 = to_one(p->k4);
    f->alpha_min = to_ang(p->alpha_min);
    f->alpha_max = to_ang(p->alpha_max);
    f->s_min = to_len(p->s_min);
    f->s_max = to_len(p->s_max);
    f->mu_min = to_one(p->mu_min);
    f->nu_min = to_one(p->nu_min);
}

/* The double parameters that the fixed ones stand for exactly. */
static void params_from_fx(const tse_fx_params *f, tse_params *p)
{
    p->L = from_len(f->L);
    p->k1 = (double)f->k1 / TSE_FX_ONE;
    p->eta = (double)f->eta / TSE_FX_RAD;
    p->k3 = (double)f->k3 / TSE_FX_ONE;
    p->k4 = (double)f->k4 / TSE_FX_ONE;
    p->alpha_min = (double)f->alpha_min / TSE_FX_RAD;
    p->alpha_max = (double)f->alpha_max / TSE_FX_RAD;
    p->s_min = from_len(f->s_min);
    p->s_max = from_len(f->s_max);
    p->mu_min = (double)f->mu_min / TSE_FX_ONE;
    p->nu_min = (double)f->nu_min / TSE_FX_ONE;
}

static void test_sincos(void **state)
{
    (void)state;
    uint64_t seed = 31;
    double worst = 0;
    for (int n = 0; n < 200000; ++n) {
        /* every int32, and a dense sample of the first turns */
        const int32_t a = n < 100000 ? (int32_t)(uint32_t)rng_next(&seed)
                                     : (int32_t)llround(rng_range(&seed, -7.0, 7.0) * TSE_FX_RAD);
        int32_t s, c;
        tse_fx_sincos(a, &s, &c);
        const long double x = (long double)a / TSE_FX_RAD;
        const double es = fabs((double)((long double)s / TSE_FX_ONE - sinl(x)));
        const double ec = fabs((double)((long double)c / TSE_FX_ONE - cosl(x)));
        if (es > worst)
            worst = es;
        if (ec > worst)
            worst = ec;
        if (!(es <= 1e-8 && ec <= 1e-8)) {
            print_error("angle %d (%.12Lg rad): sin %.12g cos %.12g, expected %.12Lg %.12Lg\n", a, x,
                        (double)s / TSE_FX_ONE, (double)c / TSE_FX_ONE, sinl(x), cosl(x));
            fail();
        }
    }
    /* The ends of the format and the quarter turns. */
    const int32_t ends[] = {INT32_MIN, INT32_MAX, 0, 1, -1, to_ang(PI / 2), to_ang(PI), to_ang(-PI), to_ang(2 * PI)};
    for (unsigned j = 0; j < sizeof ends / sizeof ends[0]; ++j) {
        int32_t s, c;
        tse_fx_sincos(ends[j], &s, &c);
        const long double x = (long double)ends[j] / TSE_FX_RAD;
        EXPECT_NEAR((double)s / TSE_FX_ONE, (double)sinl(x), 1e-8);
        EXPECT_NEAR((double)c / TSE_FX_ONE, (double)cosl(x), 1e-8);
    }
    print_message("sincos: worst error %.3g over the int32 angles and [-7, 7] rad\n", worst);
}

static int isqrt_ok(uint64_t x, uint32_t r)
{
    /* r^2 <= x < (r + 1)^2, in 128 bits */
    const unsigned __int128 r2 = (unsigned __int128)r * r, r12 = (unsigned __int128)(r + 1ull) * (r + 1ull);
    return r2 <= x && x < r12;
}

static void test_isqrt(void **state)
{
    (void)state;
    const uint64_t edges[] = {0, 1, 2, 3, 4, 15, 16, 17, UINT32_MAX, (uint64_t)UINT32_MAX * UINT32_MAX,
                              (uint64_t)UINT32_MAX * UINT32_MAX - 1, (uint64_t)UINT32_MAX * UINT32_MAX + 1,
                              UINT64_MAX, UINT64_MAX - 1, 1ull << 62, (1ull << 62) - 1, 1ull << 63};
    for (unsigned j = 0; j < sizeof edges / sizeof edges[0]; ++j)
        if (!isqrt_ok(edges[j], tse_fx_isqrt(edges[j]))) {
            print_error("isqrt(%llu) = %u\n", (unsigned long long)edges[j], tse_fx_isqrt(edges[j]));
            fail();
        }
    uint64_t seed = 5;
    for (int n = 0; n < 200000; ++n) {
        uint64_t x = rng_next(&seed) >> (rng_next(&seed) % 64);
        if (n & 1) { /* next to a square */
            const uint64_t r = x >> 32;
            x = r * r + (rng_next(&seed) % 3) - 1;
        }
        if (!isqrt_ok(x, tse_fx_isqrt(x))) {
            print_error("isqrt(%llu) = %u\n", (unsigned long long)x, tse_fx_isqrt(x));
            fail();
        }
    }
}

static void test_params(void **state)
{
    (void)state;
    tse_params p;
    tse_params_default(&p);
    tse_fx_params want, got;
    params_to_fx(&p, &want);
    tse_fx_params_default(&got);
    assert_memory_equal(&want, &got, sizeof want);
    tse_fx_geometry g;
    assert_int_equal(tse_fx_geometry_init(&g, &got), TSE_PARAM_OK);
    /* The rules of tse_params_check and the format's ranges, each naming its parameter. */
    struct {
        int field;
        double value;
        tse_param_id want;
    } bad[] = {
        {0, 0.0, TSE_PARAM_L},     {0, -1.0, TSE_PARAM_L},        {0, 4.5, TSE_PARAM_L},
        {1, 0.0, TSE_PARAM_K1},    {1, 0.1, TSE_PARAM_K1},        {1, 1.01, TSE_PARAM_K1},
        {2, 1.5708, TSE_PARAM_ETA},{2, 1.45, TSE_PARAM_ETA},      {3, -0.01, TSE_PARAM_K3},
        {4, 0.0, TSE_PARAM_K4},    {5, 0.0, TSE_PARAM_ALPHA_MIN}, {6, 0.1, TSE_PARAM_ALPHA_MAX},
        {7, -0.1, TSE_PARAM_S_MIN},{8, 0.0, TSE_PARAM_S_MAX},     {8, 8.5, TSE_PARAM_S_MAX},
        {9, 1.0, TSE_PARAM_MU_MIN},{10, -0.1, TSE_PARAM_NU_MIN},
    };
    for (unsigned j = 0; j < sizeof bad / sizeof bad[0]; ++j) {
        tse_fx_params f = got;
        int32_t *fields[] = {&f.L, &f.k1, &f.eta, &f.k3, &f.k4, &f.alpha_min, &f.alpha_max, &f.s_min, &f.s_max, &f.mu_min, &f.nu_min};
        const int is_len = bad[j].field == 0 || bad[j].field == 7 || bad[j].field == 8;
        const int is_ang = bad[j].field == 2 || bad[j].field == 5 || bad[j].field == 6;
        *fields[bad[j].field] = is_len ? to_len(bad[j].value) : is_ang ? to_ang(bad[j].value) : to_one(bad[j].value);
        tse_fx_geometry h = g;
        const tse_param_id id = tse_fx_geometry_init(&h, &f);
        if (id != bad[j].want) {
            print_error("case %u: %s, expected %s\n", j, tse_param_name(id), tse_param_name(bad[j].want));
            fail();
        }
        assert_memory_equal(&h, &g, sizeof g); /* untouched on a refusal */
    }
}

static void fx_prototype(tse_fx_geometry *gx, tse_geometry *gd, orc_geom *og)
{
    tse_fx_params f;
    tse_fx_params_default(&f);
    assert_int_equal(tse_fx_geometry_init(gx, &f), TSE_PARAM_OK);
    /* the double build and the oracle on the numbers the fixed build holds */
    tse_params p;
    params_from_fx(&f, &p);
    test_geometries(&p, gd, og);
}

static void test_worked_values(void **state)
{
    (void)state;
    tse_fx_geometry gx;
    tse_geometry gd;
    orc_geom og;
    fx_prototype(&gx, &gd, &og);
    /* kinematics.md's worked values, for the prototype's exact parameters: the fixed build holds
     * them rounded (L to 6e-8 m, k1 to 1e-9), which moves the slides by well under 0.1 um. */
    const double p1[6] = {0, 0, 1.0, 0, 0, 0}, q1 = 0.43015083911167;
    const double p2[6] = {0.1, -0.05, 1.1, 0.1, -0.05, 0.2};
    const double q2[6] = {0.39127069075903, 0.41631844093909, 0.38241559603276, 0.42099161248302, 0.56558364785006, 0.23697220292616};
    int32_t px[6];
    double back[6];
    tse_fx_ik_result r;
    pose_to_fx(p1, px, back);
    EXPECT_STATUS(tse_fx_ik(&gx, px, NULL, &r), TSE_OK);
    for (int k = 0; k < 6; ++k)
        EXPECT_NEAR(from_len(r.q[k]), q1, TOL_FX_Q);
    pose_to_fx(p2, px, back);
    EXPECT_STATUS(tse_fx_ik(&gx, px, NULL, &r), TSE_OK);
    for (int k = 0; k < 6; ++k)
        EXPECT_NEAR(from_len(r.q[k]), q2[k], TOL_FX_Q);
    /* warm from the first */
    int32_t seed[6];
    for (int k = 0; k < 6; ++k)
        seed[k] = to_len(q1);
    EXPECT_STATUS(tse_fx_ik(&gx, px, seed, &r), TSE_OK);
    for (int k = 0; k < 6; ++k)
        EXPECT_NEAR(from_len(r.q[k]), q2[k], TOL_FX_Q);
}

typedef struct {
    long poses, compared, ok, ambiguous, failures, fallbacks;
    long by_status[TSE_STATUS_COUNT];
    double max_q_err, max_mu_err, max_nu_err;
} tally;

static void report(tally *t, const double pose[6], const char *fmt, ...)
{
    t->failures++;
    if (t->failures > 12)
        return;
    char buf[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    print_error("pose " POSE_FMT ": %s\n", POSE_ARGS(pose), buf);
}

/* The oracle's "too close to call" bands at the fixed build's resolution (slides to a few units
 * of 2^-24 m; mu's room mu_guard = 2^-22 span^2). */
static orc_tol fx_tol(void)
{
    orc_tol t;
    t.len = 2e-5L;
    t.ang = 2e-4L;
    t.mu = 2e-4L;
    t.mu_noise = 8.0L * 0x1p-22L;
    t.nu = 2e-5L;
    return t;
}

/* One pose in both builds; seeds may be NULL.  The fixed pose's numbers go to the double build. */
static void compare(const tse_fx_geometry *gx, const tse_geometry *gd, const orc_geom *og, const double pose_in[6],
                    const int32_t *seed_x, const double *seed_d, tally *t, tse_fx_ik_result *rx_out,
                    tse_ik_result *rd_out)
{
    int32_t px[6];
    double pose[6];
    pose_to_fx(pose_in, px, pose);
    tse_fx_ik_result rx;
    tse_ik_result rd;
    const tse_status sx = tse_fx_ik(gx, px, seed_x, &rx);
    tse_ik(gd, pose, seed_d, &rd);
    if (rx_out)
        *rx_out = rx;
    if (rd_out)
        *rd_out = rd;
    t->poses++;
    t->fallbacks += rx.fallbacks;
    if (sx != rx.status) {
        report(t, pose, "returned %s, result %s", st_name(sx), st_name(rx.status));
        return;
    }
    t->by_status[rx.status]++;
    if (rx.status == TSE_OK) {
        t->ok++;
        for (int i = 0; i < 3; ++i)
            if (!(rx.mu[i] >= gx->p.mu_min && rx.mu[i] <= TSE_FX_ONE + 64))
                report(t, pose, "ok with mu[%d] = %.9g", i, (double)rx.mu[i] / TSE_FX_ONE);
        if (!(rx.nu >= gx->p.nu_min && rx.nu <= TSE_FX_ONE + 64))
            report(t, pose, "ok with nu = %.9g", (double)rx.nu / TSE_FX_ONE);
        for (int k = 0; k < 6; ++k)
            if (!(rx.q[k] >= gx->p.s_min && rx.q[k] <= gx->p.s_max))
                report(t, pose, "ok with q[%d] = %.9g outside the stroke", k, from_len(rx.q[k]));
    }
    orc_tol tol = fx_tol();
    orc_real po[6];
    for (int k = 0; k < 6; ++k)
        po[k] = (orc_real)pose[k];
    orc_result o;
    orc_ik(og, po, NULL, &tol, &o);
    if (o.multi) {
        orc_real pq[6];
        for (int k = 0; k < 6; ++k)
            pq[k] = (orc_real)rd.q[k];
        orc_ik(og, po, pq, &tol, &o);
    }
    if (o.ambiguous || o.multi) {
        t->ambiguous++;
    } else {
        const int any_scissor = rd.status == TSE_DEGENERATE || rd.status == TSE_OK;
        if (rx.status != rd.status || (!any_scissor && rx.scissor != rd.scissor)) {
            report(t, pose, "fixed %s/%d, double %s/%d (the oracle %s/%d)", st_name(rx.status), rx.scissor,
                   st_name(rd.status), rd.scissor, st_name(o.status), o.scissor);
            return;
        }
    }
    if (rx.status == TSE_OK && rd.status == TSE_OK && o.nsol[0] >= 1 && o.nsol[1] >= 1 && o.nsol[2] >= 1 &&
        o.mu[0] >= 0.1L && o.mu[1] >= 0.1L && o.mu[2] >= 0.1L) {
        t->compared++;
        for (int k = 0; k < 6; ++k) {
            const double e = fabs(from_len(rx.q[k]) - rd.q[k]);
            if (e > t->max_q_err)
                t->max_q_err = e;
            if (!(e <= TOL_FX_Q))
                report(t, pose, "q[%d] = %.12g, double %.12g (error %.3g m)", k, from_len(rx.q[k]), rd.q[k], e);
        }
        for (int i = 0; i < 3; ++i) {
            const double e = fabs((double)rx.mu[i] / TSE_FX_ONE - rd.mu[i]);
            if (e > t->max_mu_err)
                t->max_mu_err = e;
            if (!(e <= 1e-4)) /* as test_oracle.c asks of the float build */
                report(t, pose, "mu[%d] = %.9g, double %.9g", i, (double)rx.mu[i] / TSE_FX_ONE, rd.mu[i]);
        }
        const double e = fabs((double)rx.nu / TSE_FX_ONE - rd.nu);
        if (e > t->max_nu_err)
            t->max_nu_err = e;
        if (!(e <= 1e-4))
            report(t, pose, "nu = %.9g, double %.9g", (double)rx.nu / TSE_FX_ONE, rd.nu);
    }
}

static void print_tally(const char *name, const tally *t)
{
    print_message("%s: %ld poses, %ld ok, %ld compared (worst |q - q_double| %.3g m, mu %.3g, nu %.3g); "
                  "%ld too close to call; %ld fallbacks; %ld failures\n  statuses:",
                  name, t->poses, t->ok, t->compared, t->max_q_err, t->max_mu_err, t->max_nu_err, t->ambiguous,
                  t->fallbacks, t->failures);
    for (int s = 0; s < TSE_STATUS_COUNT; s++)
        print_message(" %s %ld", st_name(s), t->by_status[s]);
    print_message("\n");
}

static void random_pose(uint64_t *seed, double r_max, double z_lo, double z_hi, double tilt, double yaw, double pose[6])
{
    const double r = r_max * sqrt(rng_unit(seed)), ph = rng_range(seed, -PI, PI);
    pose[0] = r * cos(ph);
    pose[1] = r * sin(ph);
    pose[2] = rng_range(seed, z_lo, z_hi);
    pose[3] = rng_range(seed, -tilt, tilt);
    pose[4] = rng_range(seed, -tilt, tilt);
    pose[5] = rng_range(seed, -yaw, yaw);
}

/* test_oracle.c's sets: its seeds, ranges and counts (its poses drawn in the order written here). */
static void cold_set(const char *name, uint64_t seed, double r_max, double z_lo, double z_hi, double tilt, double yaw,
                     long min_compared, long min_ok)
{
    tse_fx_geometry gx;
    tse_geometry gd;
    orc_geom og;
    fx_prototype(&gx, &gd, &og);
    tally t;
    memset(&t, 0, sizeof t);
    for (int n = 0; n < 12000; n++) {
        double pose[6];
        random_pose(&seed, r_max, z_lo, z_hi, tilt, yaw, pose);
        compare(&gx, &gd, &og, pose, NULL, NULL, &t, NULL, NULL);
    }
    print_tally(name, &t);
    assert_int_equal(t.failures, 0);
    assert_true(t.compared >= min_compared);
    assert_true(t.ok >= min_ok);
}

/* Inside the workspace: accuracy of every accepted pose with mu >= 0.1. */
static void test_workspace_cold(void **state)
{
    (void)state;
    cold_set("workspace, cold", 20240601, 0.45, 0.3, 1.65, 0.35, 0.8, 3000, 0);
}

/* Strongly tilted and far poses: the fallback decides, and must decide as the double build. */
static void test_wide_cold(void **state)
{
    (void)state;
    cold_set("wide, cold", 77, 0.8, -0.2, 1.9, 0.9, 1.5, 0, 500);
}

static void test_trajectories_warm(void **state)
{
    (void)state;
    tse_fx_geometry gx;
    tse_geometry gd;
    orc_geom og;
    fx_prototype(&gx, &gd, &og);
    tally t;
    memset(&t, 0, sizeof t);
    uint64_t seed = 4242;
    for (int traj = 0; traj < 60; traj++) {
        double pose[6];
        random_pose(&seed, 0.3, 0.5, 1.4, 0.2, 0.5, pose);
        tse_fx_ik_result px;
        tse_ik_result pd;
        tally scratch;
        memset(&scratch, 0, sizeof scratch);
        compare(&gx, &gd, &og, pose, NULL, NULL, &scratch, &px, &pd);
        const double step = traj % 2 ? 0.002 : 0.02;
        for (int n = 0; n < 100; n++) {
            for (int k = 0; k < 6; k++)
                pose[k] += step * rng_range(&seed, -1, 1) * (k < 3 ? 1.0 : 0.5);
            const int warm = px.q[0] != TSE_FX_NONE && px.q[2] != TSE_FX_NONE && px.q[4] != TSE_FX_NONE &&
                             all_finite_q(pd.q);
            int32_t sx[6];
            double sd[6];
            memcpy(sx, px.q, sizeof sx);
            memcpy(sd, pd.q, sizeof sd);
            compare(&gx, &gd, &og, pose, warm ? sx : NULL, warm ? sd : NULL, &t, &px, &pd);
        }
    }
    print_tally("trajectories, warm", &t);
    assert_int_equal(t.failures, 0);
    assert_true(t.compared >= 3000);
}

static void test_other_designs(void **state)
{
    (void)state;
    uint64_t seed = 99;
    tally t;
    memset(&t, 0, sizeof t);
    for (int d = 0; d < 6; d++) {
        tse_params p;
        test_other_design(&seed, d, &p);
        tse_fx_params f;
        params_to_fx(&p, &f);
        tse_fx_geometry gx;
        assert_int_equal(tse_fx_geometry_init(&gx, &f), TSE_PARAM_OK);
        params_from_fx(&f, &p);
        tse_geometry gd;
        orc_geom og;
        test_geometries(&p, &gd, &og);
        for (int n = 0; n < 1500; n++) {
            double pose[6];
            random_pose(&seed, 0.4, 0.2, 1.7, 0.4, 0.8, pose);
            compare(&gx, &gd, &og, pose, NULL, NULL, &t, NULL, NULL);
        }
    }
    print_tally("other designs, cold", &t);
    assert_int_equal(t.failures, 0);
}

/* The format's edges: positions at the ends of int32 (far beyond any reach: `unreachable` at
 * scissor 1, as the double build says of a joint 128 m away), angles wrapping by whole turns,
 * a seed beyond the room (`invalid`). */
static void test_edges(void **state)
{
    (void)state;
    tse_fx_geometry gx;
    tse_geometry gd;
    orc_geom og;
    fx_prototype(&gx, &gd, &og);
    const int32_t big[] = {INT32_MAX, INT32_MIN, INT32_MAX - 1, INT32_MIN + 1};
    for (unsigned j = 0; j < 4; ++j)
        for (int axis = 0; axis < 3; ++axis) {
            int32_t pose[6] = {0, 0, to_len(1.0), INT32_MAX, INT32_MIN, INT32_MAX};
            pose[axis] = big[j];
            double pd[6];
            for (int k = 0; k < 6; ++k)
                pd[k] = k < 3 ? from_len(pose[k]) : (double)pose[k] / TSE_FX_RAD;
            tse_fx_ik_result r;
            tse_ik_result rd;
            tse_ik(&gd, pd, NULL, &rd);
            EXPECT_STATUS(tse_fx_ik(&gx, pose, NULL, &r), rd.status);
            assert_int_equal(r.scissor, rd.scissor);
            assert_int_equal(r.q[0], TSE_FX_NONE);
        }
    /* Angles wrap: a whole turn added (in the format's +-8 rad) is the same pose. */
    const double base[6] = {0.05, -0.03, 1.1, 0.1, -0.2, 0.3};
    int32_t p0[6];
    double back[6];
    pose_to_fx(base, p0, back);
    tse_fx_ik_result r0, r1;
    EXPECT_STATUS(tse_fx_ik(&gx, p0, NULL, &r0), TSE_OK);
    const int32_t turn = to_ang(2 * PI);
    for (int axis = 3; axis < 6; ++axis)
        for (int sgn = -1; sgn <= 1; sgn += 2) {
            int32_t p1[6];
            memcpy(p1, p0, sizeof p1);
            p1[axis] = (int32_t)((int64_t)p1[axis] + (int64_t)sgn * turn); /* within +-8 rad */
            EXPECT_STATUS(tse_fx_ik(&gx, p1, NULL, &r1), TSE_OK);
            /* turn is 2 pi to 2e-9 rad, and r_top (0.2 m) turns that into well under a unit */
            for (int k = 0; k < 6; ++k)
                EXPECT_NEAR(from_len(r1.q[k]), from_len(r0.q[k]), 1e-7);
        }
    /* Seeds beyond the room are malformed; at its edge they are taken. */
    int32_t seed[6];
    for (int k = 0; k < 6; ++k)
        seed[k] = r0.q[k];
    seed[3] = gx.s_box + 1;
    EXPECT_STATUS(tse_fx_ik(&gx, p0, seed, &r1), TSE_INVALID);
    assert_int_equal(r1.scissor, 1);
    seed[3] = INT32_MIN;
    EXPECT_STATUS(tse_fx_ik(&gx, p0, seed, &r1), TSE_INVALID);
    seed[3] = gx.s_box;
    EXPECT_STATUS(tse_fx_ik(&gx, p0, seed, &r1), TSE_OK);
    for (int k = 0; k < 6; ++k)
        EXPECT_NEAR(from_len(r1.q[k]), from_len(r0.q[k]), 1e-7);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sincos),         cmocka_unit_test(test_isqrt),
        cmocka_unit_test(test_params),         cmocka_unit_test(test_worked_values),
        cmocka_unit_test(test_edges),          cmocka_unit_test(test_workspace_cold),
        cmocka_unit_test(test_wide_cold),      cmocka_unit_test(test_trajectories_warm),
        cmocka_unit_test(test_other_designs),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
