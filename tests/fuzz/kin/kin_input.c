/* Decoding the kin target's bytes (kin_input.h). */
#include "kin_input.h"

#include <float.h>
#include <math.h>
#include <string.h>

typedef struct {
    const uint8_t *p;
    size_t n;
} bytes;

static unsigned take8(bytes *b)
{
    if (b->n == 0)
        return 0;
    --b->n;
    return *b->p++;
}

static unsigned take16(bytes *b)
{
    const unsigned lo = take8(b);
    return lo | take8(b) << 8;
}

static double take_double(bytes *b)
{
    uint8_t raw[8];
    for (int k = 0; k < 8; ++k)
        raw[k] = (uint8_t)take8(b);
    double x;
    memcpy(&x, raw, sizeof x);
    return x;
}

static const double awkward[32] = {
    NAN,     -NAN,     INFINITY, -INFINITY, 0.0,       -0.0,      DBL_MAX, -DBL_MAX,
    DBL_MIN, 4.9e-324, 1e300,    -1e300,    1e30,      -1e30,     1e10,    -1e10,
    FLT_MAX, 3.5e38,   -3.5e38,  FLT_MIN,   1e-300,    3.14159265358979323846,
    -3.14159265358979323846,     6.28318530717958647692, 1.57079632679489661923,
    1e6,     -1e6,     4.0,      100.0,     1e-9,      0.5,       -0.5,
};

/* One value: mostly lo..hi, sometimes four times that band around its middle, any double, or an
 * awkward one. */
static double value(bytes *b, double lo, double hi)
{
    const unsigned tag = take8(b);
    switch (tag % 8) {
    case 5:
        return 0.5 * (lo + hi) + 4.0 * (hi - lo) * ((double)take16(b) / 65535.0 - 0.5);
    case 6:
        return take_double(b);
    case 7:
        return awkward[(tag >> 3) % 32];
    default:
        return lo + (hi - lo) * (double)take16(b) / 65535.0;
    }
}

/* One parameter: mostly the prototype's, else within -30..+30 % of it (s_min: 0..0.2 m), any
 * double or an awkward one. */
static double parameter(bytes *b, double def, int *plausible)
{
    const unsigned tag = take8(b);
    switch (tag % 8) {
    case 4:
    case 5: {
        const double f = (double)take8(b) / 255.0;
        return def == 0.0 ? 0.2 * f : def * (0.7 + 0.6 * f);
    }
    case 6:
        *plausible = 0;
        return take_double(b);
    case 7:
        *plausible = 0;
        return awkward[(tag >> 3) % 32];
    default:
        return def;
    }
}

void kin_decode(const uint8_t *data, size_t size, kin_case *c)
{
    memset(c, 0, sizeof *c);
    bytes b = {data, size};
    const unsigned flags = take8(&b);
    c->run_double = (flags & 3) != 2;
    c->run_float = (flags & 3) != 1;
    c->ik_seeded = (flags >> 2) & 1;
    c->run_fk = (flags >> 3) & 1;
    c->fk_seeded = (flags >> 4) & 1;
    c->fuzz_params = (flags >> 5) & 1;
    c->fk_mode = (fk_slides)(flags >> 6);

    side_default_d(c->params);
    c->plausible_params = 1;
    if (c->fuzz_params)
        for (int k = 0; k < SIDE_NPARAMS; ++k)
            c->params[k] = parameter(&b, c->params[k], &c->plausible_params);
    /* A pose near this design's workspace. */
    const double L = isfinite(c->params[0]) && c->params[0] > 0 && c->params[0] < 1e6 ? c->params[0] : 1.727;
    const double lo[6] = {-0.3 * L, -0.3 * L, 0.1 * L, -0.4, -0.4, -1.0};
    const double hi[6] = {0.3 * L, 0.3 * L, 1.0 * L, 0.4, 0.4, 1.0};
    for (int k = 0; k < 6; ++k)
        c->pose[k] = value(&b, lo[k], hi[k]);
    if (c->ik_seeded) {
        c->warm_ik_seed = take8(&b) & 1;
        for (int k = 0; k < 6; ++k)
            c->ik_seed[k] = c->warm_ik_seed ? 1e-4 * (double)(int8_t)take8(&b) : value(&b, 0.0, 0.55 * L);
    }
    if (c->run_fk) {
        for (int k = 0; k < 6; ++k) {
            if (c->fk_mode == FK_SLIDES_ANY)
                c->fk_slides[k] = value(&b, 0.0, 0.55 * L);
            else if (c->fk_mode != FK_SLIDES_SAME)
                c->fk_slides[k] = (c->fk_mode == FK_SLIDES_NUDGED ? 1e-7 : 1e-4) * (double)(int8_t)take8(&b);
        }
        if (c->fk_seeded) {
            c->fk_seed_at_pose = take8(&b) & 1;
            for (int k = 0; k < 6; ++k)
                c->fk_seed[k] = c->fk_seed_at_pose ? c->pose[k] : value(&b, lo[k], hi[k]);
        }
    }
}
