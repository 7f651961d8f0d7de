/* Host program, run by the Cortex-M3 build: writes kin_table_fixed.c (kin_table_fixed.h), the
 * poses the fixed-point IK is checked against on the target.  The design is the prototype as the
 * fixed build holds it (tse_fx_params_default's rounding, redone here from tse/prototype.h), in
 * double; the expectations are the double build's and the oracle's.  Poses come in short warm
 * paths through the workspace and, from no seed, over a wider range that reaches every status.
 *   gen_kin_table_fixed OUTPUT.c */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "oracle.h"
#include "tse/geometry.h"
#include "tse/ik.h"
#include "tse/prototype.h"

#define PATHS 150
#define WALK 4
#define WIDE 400
#define Q24 16777216.0
#define Q28 268435456.0
#define Q30 1073741824.0

static uint64_t rng = 20261128;
static double unit(void)
{
    uint64_t z = (rng += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return (double)((z ^ (z >> 31)) >> 11) * (1.0 / 9007199254740992.0);
}
static double range(double lo, double hi)
{
    return lo + (hi - lo) * unit();
}
static double fx(double x, double s)
{
    return nearbyint(x * s) / s;
}

static tse_geometry g;
static orc_geom og;
static FILE *out;
static unsigned count;

static void emit(double pose_in[6], int path_start)
{
    double pose[6];
    for (int k = 0; k < 6; ++k)
        pose[k] = fx(pose_in[k], k < 3 ? Q24 : Q28);
    tse_ik_result r;
    tse_ik(&g, pose, NULL, &r);
    orc_tol tol = {2e-5L, 2e-4L, 2e-4L, 8.0L * 0x1p-22L, 2e-5L};
    orc_real po[6];
    for (int k = 0; k < 6; ++k)
        po[k] = pose[k];
    orc_result o;
    orc_ik(&og, po, NULL, &tol, &o);
    const int clear = !o.ambiguous && !o.multi;
    const int accurate = clear && r.status == TSE_OK && o.mu[0] >= 0.1L && o.mu[1] >= 0.1L && o.mu[2] >= 0.1L;
    fprintf(out, "    {{");
    for (int k = 0; k < 6; ++k)
        fprintf(out, "%s%.0f", k ? ", " : "", pose[k] * (k < 3 ? Q24 : Q28));
    fprintf(out, "}, {");
    for (int k = 0; k < 6; ++k) {
        if (isfinite(r.q[k]))
            fprintf(out, "%s%.0f", k ? ", " : "", nearbyint(r.q[k] * Q24));
        else
            fprintf(out, "%sINT32_MIN", k ? ", " : "");
    }
    fprintf(out, "}, %d, %d, %d, %d, %d},\n", path_start, (int)r.status, r.scissor, clear, accurate);
    ++count;
}

int main(int argc, char **argv)
{
    if (argc != 2)
        return 2;
    tse_params p;
    tse_params_default(&p);
    p.L = fx(TSE_PROTO_L, Q24);
    p.k1 = fx(TSE_PROTO_K1, Q30);
    p.eta = fx(TSE_PROTO_ETA, Q28);
    p.k3 = fx(TSE_PROTO_K3, Q30);
    p.k4 = fx(TSE_PROTO_K4, Q30);
    p.alpha_min = fx(TSE_PROTO_ALPHA_MIN, Q28);
    p.alpha_max = fx(TSE_PROTO_ALPHA_MAX, Q28);
    p.s_min = fx(TSE_PROTO_S_MIN, Q24);
    p.s_max = fx(TSE_PROTO_S_MAX, Q24);
    p.mu_min = fx(TSE_PROTO_MU_MIN, Q30);
    p.nu_min = fx(TSE_PROTO_NU_MIN, Q30);
    if (tse_geometry_init(&g, &p) != TSE_PARAM_OK)
        return 1;
    orc_params op = {p.L, p.k1, p.eta, p.k3, p.k4, p.alpha_min, p.alpha_max, p.s_min, p.s_max, p.mu_min, p.nu_min};
    orc_geom_init(&og, &op);
    out = fopen(argv[1], "w");
    if (!out)
        return 1;
    fprintf(out, "/* Written by gen_kin_table_fixed (tests/target_m3): do not edit. */\n"
                 "#include \"kin_table_fixed.h\"\n\nconst kin_fx_case kin_fx_cases[] = {\n");
    const double pi = 3.14159265358979323846;
    for (int n = 0; n < PATHS; ++n) {
        const double r = 0.3 * sqrt(unit()), ph = range(-pi, pi);
        double pose[6] = {r * cos(ph), r * sin(ph), range(0.5, 1.4), range(-0.2, 0.2), range(-0.2, 0.2), range(-0.5, 0.5)};
        for (int w = 0; w < WALK; ++w) {
            if (w)
                for (int k = 0; k < 6; ++k)
                    pose[k] += 0.002 * range(-1, 1) * (k < 3 ? 1.0 : 0.5);
            emit(pose, w == 0);
        }
    }
    for (int n = 0; n < WIDE; ++n) {
        const double r = 0.8 * sqrt(unit()), ph = range(-pi, pi);
        double pose[6] = {r * cos(ph), r * sin(ph), range(-0.2, 1.9), range(-0.9, 0.9), range(-0.9, 0.9), range(-1.5, 1.5)};
        emit(pose, 1);
    }
    fprintf(out, "};\nconst unsigned kin_fx_case_count = %u;\n", count);
    return fclose(out) != 0;
}
