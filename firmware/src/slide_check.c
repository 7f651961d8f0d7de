#include "fw/slide_check.h"

void fw_slide_check_start(fw_slide_check *c, tse_real vmax, tse_real amax, tse_real segment_hz,
                          const tse_real q_start[6])
{
    c->vmax = vmax;
    c->amax = amax;
    c->segment_hz = segment_hz;
    for (int k = 0; k < 6; ++k)
        c->q[k] = q_start[k];
    for (uint32_t j = 0; j < FW_ACC_STRIDE; ++j)
        for (int k = 0; k < 6; ++k)
            c->vel[j][k] = TSE_R(0.0);
    c->n = 0;
    c->v_ratio = TSE_R(0.0);
    c->a_ratio = TSE_R(0.0);
}

static void push_velocity(fw_slide_check *c, const tse_real v[6])
{
    /* The ring slot of setpoint n still holds setpoint n - FW_ACC_STRIDE (rest at the start). */
    tse_real *old = c->vel[c->n % FW_ACC_STRIDE];
    for (int k = 0; k < 6; ++k) {
        const tse_real a = (v[k] - old[k]) * c->segment_hz / (tse_real)FW_ACC_STRIDE;
        const tse_real ar = tse_fabs(a) / c->amax;
        if (ar > c->a_ratio)
            c->a_ratio = ar;
        old[k] = v[k];
    }
    ++c->n;
}

void fw_slide_check_feed(fw_slide_check *c, const tse_real q[6], tse_real dt)
{
    tse_real v[6];
    for (int k = 0; k < 6; ++k) {
        v[k] = dt > TSE_R(0.0) ? (q[k] - c->q[k]) / dt : TSE_R(0.0);
        const tse_real vr = tse_fabs(v[k]) / c->vmax;
        if (vr > c->v_ratio)
            c->v_ratio = vr;
        c->q[k] = q[k];
    }
    push_velocity(c, v);
}

void fw_slide_check_finish(fw_slide_check *c)
{
    static const tse_real rest[6] = {0};
    for (uint32_t j = 0; j < FW_ACC_STRIDE; ++j)
        push_velocity(c, rest);
}
