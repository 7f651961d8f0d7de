/* Instruction counts of the fixed-point inverse kinematics on the emulated Cortex-M3 (QEMU
 * mps2-an385 with -icount shift=6: an instruction is 64 ns of virtual time, and SysTick, on the
 * 25 MHz core clock, gains 1.6 counts per instruction).  The scale is not taken on trust: a block
 * of 1,000 nops is counted first, and every figure is (count - overhead) * 1000 / (that count -
 * overhead).  Prints `name,instructions` (the median over the calls; a benchmark, never a test):
 * ik_fixed_warm along the M4F benchmark's path (bench/target/target_bench.c, path_pose, here in
 * integers), seeded with the previous answer, and ik_fixed_cold from no seed on every other pose. */
#include <stdint.h>

#include "hal_mps2/m3.h"
#include "tse/ik_fixed.h"

#define N 1000
static uint32_t samples[N];
static uint32_t overhead, per_1000;

static void sort(uint32_t *v, unsigned n)
{
    for (unsigned i = 1; i < n; ++i) {
        const uint32_t x = v[i];
        unsigned j = i;
        for (; j > 0 && v[j - 1] > x; --j)
            v[j] = v[j - 1];
        v[j] = x;
    }
}

static uint32_t instructions(uint32_t counts)
{
    return (uint32_t)(((uint64_t)(counts - overhead) * 1000u + per_1000 / 2u) / per_1000);
}

static void report(const char *name, unsigned n)
{
    sort(samples, n);
    m3_puts(name);
    m3_puts(",");
    m3_put_int(instructions(samples[n / 2]));
    m3_puts("\n");
}

static void calibrate(void)
{
    uint32_t lo = UINT32_MAX;
    for (int i = 0; i < 16; ++i) {
        const uint32_t a = m3_cycles();
        const uint32_t b = m3_cycles();
        if (((b - a) & 0xFFFFFFu) < lo)
            lo = (b - a) & 0xFFFFFFu;
    }
    overhead = lo;
    const uint32_t a = m3_cycles();
    __asm__ volatile(".rept 1000\n nop\n .endr" ::: "memory");
    const uint32_t b = m3_cycles();
    per_1000 = ((b - a) & 0xFFFFFFu) - overhead;
}

/* sin(k t) of the path in Q30, t = 2 pi i / N. */
static int32_t sin_of(unsigned i, int k, int32_t phase_q28, int cosine)
{
    const int64_t two_pi_q28 = 1686629713LL; /* 2 pi in Q28 */
    const int32_t a = (int32_t)((two_pi_q28 * (int64_t)(i * (unsigned)k) / N) % two_pi_q28) + phase_q28;
    int32_t s, c;
    tse_fx_sincos(a, &s, &c);
    return cosine ? c : s;
}

/* The M4F benchmark's Lissajous figure: (0.08 sin t, 0.06 sin 2t, 1.05 + 0.15 sin 3t,
 * 0.05 sin(t + 0.3), 0.05 cos 2t, 0.1 sin t). */
static void path_pose(unsigned i, int32_t p[6])
{
    const int64_t m = TSE_FX_M, rad = TSE_FX_RAD;
    p[0] = (int32_t)((m * 8 / 100 * sin_of(i, 1, 0, 0)) >> 30);
    p[1] = (int32_t)((m * 6 / 100 * sin_of(i, 2, 0, 0)) >> 30);
    p[2] = (int32_t)(m * 105 / 100 + ((m * 15 / 100 * sin_of(i, 3, 0, 0)) >> 30));
    p[3] = (int32_t)((rad * 5 / 100 * sin_of(i, 1, (int32_t)(rad * 3 / 10), 0)) >> 30);
    p[4] = (int32_t)((rad * 5 / 100 * sin_of(i, 2, 0, 1)) >> 30);
    p[5] = (int32_t)((rad * 10 / 100 * sin_of(i, 1, 0, 0)) >> 30);
}

int main(void)
{
    m3_counter_start();
    calibrate();
    static tse_fx_geometry g;
    tse_fx_params p;
    tse_fx_params_default(&p);
    if (tse_fx_geometry_init(&g, &p) != TSE_PARAM_OK)
        return 1;
    tse_fx_ik_result r;
    int32_t pose[6], q[6];
    path_pose(0, pose);
    tse_fx_ik(&g, pose, 0, &r);
    for (int k = 0; k < 6; ++k)
        q[k] = r.q[k];
    unsigned warm = 0, cold = 0, refused = 0;
    for (unsigned i = 1; i <= N; ++i) {
        path_pose(i, pose);
        const uint32_t t0 = m3_cycles();
        tse_fx_ik(&g, pose, q, &r);
        const uint32_t t1 = m3_cycles();
        if (r.status == TSE_OK) {
            samples[warm++] = (t1 - t0) & 0xFFFFFFu;
            for (int k = 0; k < 6; ++k)
                q[k] = r.q[k];
        } else {
            ++refused;
        }
    }
    m3_puts("# instruction counts on the emulated Cortex-M3 (QEMU mps2-an385, -icount shift=6, SysTick), medians; 1000 nops counted ");
    m3_put_int(per_1000);
    m3_puts(", read overhead ");
    m3_put_int(overhead);
    m3_puts("\n");
    report("ik_fixed_warm", warm);
    for (unsigned i = 1; i <= N; i += 2) {
        path_pose(i, pose);
        const uint32_t t0 = m3_cycles();
        tse_fx_ik(&g, pose, 0, &r);
        const uint32_t t1 = m3_cycles();
        if (r.status == TSE_OK)
            samples[cold++] = (t1 - t0) & 0xFFFFFFu;
    }
    report("ik_fixed_cold", cold);
    if (refused) {
        m3_puts("# poses of the path refused: ");
        m3_put_int(refused);
        m3_puts("\n");
    }
    return 0;
}
