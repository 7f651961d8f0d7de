#include "fw/slide_check.h"

void fw_slide_check_start(fw_slide_check *c, tse_real vmax, tse_real amax, tse_real segment_hz,
                          const tse_real q_start[6])
{
    c->vmax = vmax;
    c->amax = amax;
    c->segment_hz = segment_hz;
    for (int k = 0; k < 6; ++k)
        c->q[k] = q_start[k];
    for (uint32_t j = 0; j < 2 * FW_ACC_STRIDE; ++j)
        for (int k = 0; k < 6; ++k)
            c->hist[j][k] = q_start[k];
    c->n = 0;
    c->v_ratio = TSE_R(0.0);
    c->a_ratio = TSE_R(0.0);
    c->v_slide = 0;
    c->a_slide = 0;
}

static void push(fw_slide_check *c, const tse_real q[6])
{
    /* The ring slot of setpoint n holds setpoint n - 2S; slot n - S (mod 2S) holds n - S. */
    const uint32_t S = FW_ACC_STRIDE;
    tse_real *old2 = c->hist[c->n % (2 * S)];
    const tse_real *old1 = c->hist[(c->n + S) % (2 * S)];
    const tse_real span = (tse_real)S / c->segment_hz;
    for (int k = 0; k < 6; ++k) {
        const tse_real a = (q[k] - TSE_R(2.0) * old1[k] + old2[k]) / (span * span);
        const tse_real ar = tse_fabs(a) / c->amax;
        if (ar > c->a_ratio) {
            c->a_ratio = ar;
            c->a_slide = (uint8_t)k;
        }
        old2[k] = q[k];
    }
    ++c->n;
}

void fw_slide_check_feed(fw_slide_check *c, const tse_real q[6], tse_real dt)
{
    for (int k = 0; k < 6; ++k) {
        const tse_real v = dt > TSE_R(0.0) ? (q[k] - c->q[k]) / dt : TSE_R(0.0);
        const tse_real vr = tse_fabs(v) / c->vmax;
        if (vr > c->v_ratio) {
            c->v_ratio = vr;
            c->v_slide = (uint8_t)k;
        }
        c->q[k] = q[k];
    }
    push(c, q);
}

void fw_slide_check_finish(fw_slide_check *c)
{
    tse_real rest[6];
    for (int k = 0; k < 6; ++k)
        rest[k] = c->q[k];
    for (uint32_t j = 0; j < 2 * FW_ACC_STRIDE; ++j)
        push(c, rest);
}

bool fw_slide_check_ok(const fw_slide_check *c)
{
    return !(c->v_ratio > TSE_R(1.0) || c->a_ratio > TSE_R(1.0));
}

fw_slide_worst fw_slide_check_worst(const fw_slide_check *c)
{
    fw_slide_worst w;
    w.accel = c->a_ratio > c->v_ratio;
    w.slide = w.accel ? c->a_slide : c->v_slide;
    w.ratio = w.accel ? c->a_ratio : c->v_ratio;
    return w;
}
