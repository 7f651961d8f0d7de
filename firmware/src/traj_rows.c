#include "traj_rows.h"

#include "publish.h"
#include "send.h"

void fw_rows_collect(fw_controller *c)
{
    fw_thread *th = &c->th;
    fw_traj_ended e;
    while (fw_ended_take(c, &e)) {
        if (th->open && e.id == th->id)
            th->open = false;
        th->ended = (fw_traj_end)e.how;
        th->ended_fault = (fw_fault)e.fault;
        th->ended_id = e.id;
        th->ended_rows = e.rows;
        th->ended_us = e.us;
        const int32_t v[4] = {e.id, e.how, e.fault, (int32_t)(e.rows > 16777215u ? 16777215u : e.rows)};
        fw_send(c, PM_TRAJ_END, v);
    }
}

void fw_rows_took(fw_controller *c, uint8_t seq, bool first, uint8_t id)
{
    fw_thread *th = &c->th;
    if (first) {
        th->open = true;
        th->id = id;
    }
    th->next_seq = (uint8_t)(seq + 1u);
}

fw_reason fw_rows_refusal(const fw_controller *c, const proto_message *m, bool ended_only, uint8_t *field,
                          int32_t *where)
{
    const fw_thread *th = &c->th;
    const uint8_t seq = (uint8_t)m->v[0], id = (uint8_t)m->v[3];
    *field = 0;
    *where = 0;
    if (m->v[2] & PROTO_TRAJ_FIRST)
        return FW_REASON_NONE; /* a first row begins a trajectory: the state decides */
    if (th->open && id == th->id) {
        if (ended_only || seq == th->next_seq)
            return FW_REASON_NONE;
        *field = th->next_seq;
        return FW_REASON_ORDER;
    }
    if (th->ended != FW_TRAJ_END_NONE && id == th->ended_id) {
        /* For an underrun, the time since it is how late the host was with this row. */
        const uint64_t ms = (fw_now(c) - th->ended_us) / 1000u;
        *field = (uint8_t)(th->ended + 16u * (unsigned)th->ended_fault);
        *where = ms > 65535u ? 65535 : (int32_t)ms;
        return FW_REASON_ENDED;
    }
    return ended_only ? FW_REASON_NONE : FW_REASON_ENDED; /* no trajectory of that identity runs */
}
