#include "telemetry.h"

#include "publish.h"
#include "send.h"
#include "tse/fk.h"

static void send_status(fw_controller *c, const fw_view *v)
{
    uint8_t flags = 0;
    if (v->flags & FW_VIEW_HOMED)
        flags |= PROTO_STATUS_HOMED;
    /* An e-stop's halt has switched the drives off already, ahead of the tick that completes it
     * (fw/runtime.h): a STATUS sent meanwhile (a look at the bus during an ESTOP's hand-over) says
     * so, not the drives of the view the tick last published. */
    if ((v->flags & FW_VIEW_DRIVES) && !atomic_load(&c->sh.estop_request))
        flags |= PROTO_STATUS_DRIVES;
    if (v->flags & FW_VIEW_ESTOP_IN)
        flags |= PROTO_STATUS_ESTOP_IN;
    if (v->flags & FW_VIEW_SWITCHES_OFF)
        flags |= PROTO_STATUS_SWITCHES_OFF;
    if (v->flags & FW_VIEW_ERROR_PASSIVE)
        flags |= PROTO_STATUS_ERROR_PASSIVE;
    const int32_t s[7] = {v->state, v->fault, flags, (int32_t)v->traj_depth,
                          (int32_t)(FW_TRAJ_CAPACITY - v->traj_depth), c->th.last_seq, c->th.counter++};
    fw_send(c, PM_STATUS, s);
}

/* A slide position in the wire's nanometres.  The stroke may reach 5 m, beyond what an i32 of
 * nanometres holds (2.147 m): past it the field's end is sent, not an undefined conversion. */
static int32_t wire_nm(tse_real s)
{
    const tse_real nm = s * (tse_real)PROTO_NM_PER_M;
    if (nm >= TSE_R(2147483647.0))
        return INT32_MAX;
    if (nm <= TSE_R(-2147483648.0))
        return INT32_MIN;
    return (int32_t)nm;
}

static void send_telemetry(fw_controller *c, const fw_view *v)
{
    tse_real q[6];
    const tse_real spm = (tse_real)c->th.params.v[FP_STEPS_PER_M];
    for (int k = 0; k < 6; ++k)
        q[k] = (tse_real)v->pos[k] / spm;
    for (int k = 0; k < 3; ++k) {
        const int32_t s[2] = {wire_nm(q[2 * k]), wire_nm(q[2 * k + 1])};
        fw_send(c, (proto_msg)(PM_SLIDES_A + k), s);
    }
    if (!(v->flags & FW_VIEW_HOMED))
        return; /* no zero, no pose */
    tse_fk_result fk;
    const tse_real *seed = (v->flags & FW_VIEW_POSE_KNOWN) ? v->pose : c->th.geom.home_pose;
    if (tse_fk(&c->th.geom, q, seed, &fk) != TSE_OK)
        return;
    for (int k = 0; k < 3; ++k) {
        const int32_t s[2] = {(int32_t)(fk.pose[2 * k] * (tse_real)proto_pose_units(2 * k)),
                              (int32_t)(fk.pose[2 * k + 1] * (tse_real)proto_pose_units(2 * k + 1))};
        fw_send(c, (proto_msg)(PM_FK_A + k), s);
    }
}

static bool status_due(const fw_thread *th, uint64_t t)
{
    return t >= th->next_status_us;
}

static bool telemetry_due(const fw_thread *th, uint64_t t)
{
    return th->params.v[FP_TELEMETRY_MS] > 0 && t >= th->next_telemetry_us;
}

static void send_due(fw_controller *c, const fw_view *v, uint64_t t)
{
    fw_thread *th = &c->th;
    if (status_due(th, t)) {
        send_status(c, v);
        th->next_status_us = t + (uint64_t)th->params.v[FP_STATUS_MS] * 1000u;
    }
    if (telemetry_due(th, t)) {
        send_telemetry(c, v);
        th->next_telemetry_us = t + (uint64_t)th->params.v[FP_TELEMETRY_MS] * 1000u;
    }
}

void fw_telemetry_poll(fw_controller *c)
{
    send_due(c, &c->th.view, fw_now(c));
}

void fw_telemetry_look(fw_controller *c)
{
    const uint64_t t = fw_now(c);
    if (!status_due(&c->th, t) && !telemetry_due(&c->th, t))
        return; /* the common case: a look costs no view */
    fw_view v;
    fw_view_read_into(c, &v);
    send_due(c, &v, t);
}
