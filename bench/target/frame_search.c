/* The search for the costliest MOVE_COMMIT frames on the emulated Cortex-M4F (run by
 * scripts/frame_search.sh; docs/validation.md, "What one frame costs").  Each candidate is measured
 * as target_bench measures frame_worst (bench_commit_cost: the frame's handling whole, in guest
 * instructions, float, release flags).  Candidates, from rest at the home pose or at a pose near the
 * workspace's edge:
 *   edge    to a pose on a random ray from home, just inside or just outside the workspace (within
 *           +-2 % of the ray's boundary), at any duration from 1 ms to an hour or any speed;
 *   far     to a pose far outside it (up to the wire's 4 m, 3 rad), slow or long;
 *   chord   along a chord through a point just inside or outside the boundary, from a pose inside
 *           it (the tangent paths that make pieces small for long);
 *   turn    rotations only, to an orientation near the boundary;
 * then the costliest are mutated (target moved by up to 1 % of its ray, the value scaled) and kept
 * when they cost more.  Prints the costliest as bench_commit initializers for frame_cases.c, and the
 * commit, of all tried, that held the board longest from the bus (bench_hold_end: frame_worst). */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "bench_rig.h"
#include "hal_stm32f4/semihost.h"
#include "tse/ik.h"

#define FAMILIES 4
#define CANDIDATES 1200
#define MUTATIONS 800
#define KEEP 6 /* per family: mutants join their parent's */

typedef struct {
    bench_commit bc;
    uint32_t cost;
    char answer;
    int reason;
    bool mutant;
} found;

static found best[FAMILIES][KEEP];
static unsigned nbest[FAMILIES];
static const char *const family_name[FAMILIES] = {"edge", "far", "chord", "turn"};

static uint64_t rng = 0x243F6A8885A308D3ull;

static uint32_t next32(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return (uint32_t)(rng >> 32);
}

static tse_real uniform(tse_real lo, tse_real hi)
{
    return lo + (hi - lo) * (tse_real)(next32() >> 8) * TSE_R(5.9604645e-8); /* 2^-24 */
}

/* 10^uniform(lo, hi) */
static tse_real log_uniform(tse_real lo, tse_real hi)
{
    return expf(uniform(lo, hi) * TSE_R(2.302585093));
}

static bool reachable(const tse_real p[6])
{
    tse_ik_result r;
    return tse_ik(fw_geometry_of(bench_ctl), p, NULL, &r) == TSE_OK;
}

/* The largest t in [0, 1] along p0 + t dir that the solver still takes, by bisection. */
static tse_real boundary(const tse_real p0[6], const tse_real dir[6])
{
    tse_real lo = TSE_R(0.0), hi = TSE_R(1.0);
    for (int it = 0; it < 24; ++it) {
        const tse_real mid = TSE_R(0.5) * (lo + hi);
        tse_real p[6];
        for (int k = 0; k < 6; ++k)
            p[k] = p0[k] + mid * dir[k];
        if (reachable(p))
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

static void random_dir(tse_real dir[6], tse_real scale)
{
    static const tse_real span[6] = {TSE_R(0.6), TSE_R(0.6), TSE_R(1.0), TSE_R(0.8), TSE_R(0.8), TSE_R(2.0)};
    for (int k = 0; k < 6; ++k)
        dir[k] = scale * span[k] * uniform(TSE_R(-1.0), TSE_R(1.0));
}

static void random_value(bench_commit *bc, bool slow)
{
    bc->kind = (next32() & 3u) == 0 ? 1 : 0;
    if (bc->kind == 0)
        bc->value = (int32_t)log_uniform(slow ? TSE_R(4.0) : TSE_R(0.0), TSE_R(6.556)); /* 1 ms .. 1 h */
    else
        bc->value = (int32_t)log_uniform(TSE_R(0.0), slow ? TSE_R(3.0) : TSE_R(6.0)); /* 1 um/s .. 1 m/s */
    if (bc->value < 1)
        bc->value = 1;
}

static void candidate(int family, bench_commit *bc)
{
    const tse_real *home = fw_geometry_of(bench_ctl)->home_pose;
    tse_real dir[6];
    memcpy(bc->from, home, sizeof bc->from);
    switch (family) {
    case 0: {
        random_dir(dir, TSE_R(1.0));
        const tse_real t = boundary(home, dir) * (TSE_R(1.0) + uniform(TSE_R(-0.02), TSE_R(0.02)));
        for (int k = 0; k < 6; ++k)
            bc->to[k] = home[k] + t * dir[k];
        random_value(bc, false);
        break;
    }
    case 1:
        random_dir(dir, TSE_R(4.0));
        for (int k = 0; k < 6; ++k)
            bc->to[k] = home[k] + dir[k];
        bc->to[2] = uniform(TSE_R(-1.0), TSE_R(4.0));
        random_value(bc, true);
        break;
    case 2: {
        random_dir(dir, TSE_R(1.0));
        const tse_real t = boundary(home, dir) * (TSE_R(1.0) + uniform(TSE_R(-0.01), TSE_R(0.01)));
        tse_real side[6];
        random_dir(side, uniform(TSE_R(0.02), TSE_R(0.2)));
        for (int k = 0; k < 6; ++k) {
            const tse_real edge = home[k] + t * dir[k];
            bc->from[k] = edge - side[k];
            bc->to[k] = edge + side[k];
        }
        random_value(bc, false);
        break;
    }
    default: {
        random_dir(dir, TSE_R(1.0));
        dir[0] = dir[1] = dir[2] = TSE_R(0.0);
        const tse_real t = boundary(home, dir) * (TSE_R(1.0) + uniform(TSE_R(-0.02), TSE_R(0.02)));
        for (int k = 0; k < 6; ++k)
            bc->to[k] = home[k] + t * dir[k];
        random_value(bc, false);
        break;
    }
    }
}

static void mutate(const bench_commit *a, bench_commit *bc)
{
    *bc = *a;
    for (int k = 0; k < 6; ++k)
        bc->to[k] += TSE_R(0.01) * (bc->to[k] - bc->from[k]) * uniform(TSE_R(-1.0), TSE_R(1.0));
    const tse_real scaled = (tse_real)bc->value * log_uniform(TSE_R(-0.5), TSE_R(0.5));
    const int32_t most = bc->kind == 0 ? 3600000 : 1000000;
    bc->value = scaled < TSE_R(1.0) ? 1 : scaled > (tse_real)most ? most : (int32_t)scaled;
}

static bench_commit held;
static uint32_t held_for;

static void keep(const bench_commit *bc, int family, bool mutant)
{
    char answer;
    int reason;
    uint32_t hold;
    const uint32_t cost = bench_commit_cost(bc, &answer, &reason, &hold);
    if (cost == 0)
        return; /* its start is not reachable */
    if (hold > held_for) {
        held_for = hold;
        held = *bc;
    }
    found *b = best[family];
    unsigned i = nbest[family] < KEEP ? nbest[family]++ : KEEP - 1;
    if (i == KEEP - 1 && nbest[family] == KEEP && b[i].cost >= cost)
        return;
    while (i > 0 && b[i - 1].cost < cost) {
        b[i] = b[i - 1];
        --i;
    }
    b[i] = (found){*bc, cost, answer, reason, mutant};
}

static void print_real(tse_real x)
{
    /* %f is not in newlib-nano's printf: micro-units as integers. */
    const int32_t u = (int32_t)(x * TSE_R(1e6) + (x >= TSE_R(0.0) ? TSE_R(0.5) : TSE_R(-0.5)));
    sh_printf("%s%ld.%06ld", u < 0 ? "-" : "", (long)(u < 0 ? -u : u) / 1000000, (long)(u < 0 ? -u : u) % 1000000);
}

static void print_pose(const tse_real p[6])
{
    sh_puts("{");
    for (int k = 0; k < 6; ++k) {
        print_real(p[k]);
        sh_puts(k < 5 ? ", " : "}");
    }
}

int main(void)
{
    bench_counter_start();
    if (bench_rig_start() != 0) {
        sh_puts("frame_search: controller did not start\n");
        sh_exit(1);
    }
    unsigned tried[FAMILIES] = {0};
    for (int i = 0; i < CANDIDATES; ++i) {
        const int family = (int)(next32() % FAMILIES);
        bench_commit bc;
        candidate(family, &bc);
        ++tried[family];
        keep(&bc, family, false);
    }
    for (int i = 0; i < MUTATIONS; ++i) {
        const int family = (int)(next32() % FAMILIES);
        if (nbest[family] == 0)
            continue;
        bench_commit bc;
        mutate(&best[family][next32() % nbest[family]].bc, &bc);
        keep(&bc, family, true);
    }
    sh_printf("# %u edge, %u far, %u chord, %u turn candidates and %u mutants of the costliest; the costliest of each "
              "kind:\n", tried[0], tried[1], tried[2], tried[3], MUTATIONS);
    for (int family = 0; family < FAMILIES; ++family)
        for (unsigned i = 0; i < nbest[family]; ++i) {
            const found *f = &best[family][i];
            sh_puts("    {");
            print_pose(f->bc.from);
            sh_puts(", ");
            print_pose(f->bc.to);
            sh_printf(", %ld, %ld}, /* %lu instructions, %s%s, %s */\n", (long)f->bc.kind, (long)f->bc.value,
                      (unsigned long)f->cost, family_name[family], f->mutant ? " (mutated)" : "",
                      f->answer == 'a'   ? "accepted"
                      : f->answer == 'r' ? proto_enum_name(proto_reason_names, f->reason)
                                         : "no answer");
        }
    sh_puts("# held the board longest from the bus:\n    {");
    print_pose(held.from);
    sh_puts(", ");
    print_pose(held.to);
    sh_printf(", %ld, %ld}, /* held %lu instructions */\n", (long)held.kind, (long)held.value, (unsigned long)held_for);
    sh_exit(0);
}
