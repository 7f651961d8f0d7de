#include "publish.h"

#include <string.h>

void fw_publish(fw_controller *c)
{
    const fw_tick *t = &c->tick;
    fw_view v;
    memset(&v, 0, sizeof v);
    v.state = (uint8_t)t->state;
    v.fault = (uint8_t)t->fault;
    v.src = (uint8_t)t->src;
    v.flags = (uint8_t)((t->homed ? FW_VIEW_HOMED : 0u) | (t->drives_on ? FW_VIEW_DRIVES : 0u) |
                        (t->pose_known ? FW_VIEW_POSE_KNOWN : 0u) | (t->stopping ? FW_VIEW_STOPPING : 0u) |
                        (t->has_next ? FW_VIEW_HAS_NEXT : 0u) | (t->estop_in ? FW_VIEW_ESTOP_IN : 0u) |
                        (t->switches_off ? FW_VIEW_SWITCHES_OFF : 0u) |
                        (t->error_passive ? FW_VIEW_ERROR_PASSIVE : 0u));
    v.traj_depth = fw_traj_queue_depth(&t->traj);
    v.segments_run = t->segments_run;
    stepgen_positions(&c->sg, v.pos);
    for (int k = 0; k < 6; ++k) {
        v.pose[k] = t->pose[k];
        v.q[k] = t->q[k];
    }
    uint32_t w[FW_VIEW_WORDS];
    memset(w, 0, sizeof w);
    memcpy(w, &v, sizeof v);
    fw_shared *s = &c->sh;
    const uint32_t seq = atomic_load_explicit(&s->view_seq, memory_order_relaxed);
    atomic_store_explicit(&s->view_seq, seq + 1u, memory_order_relaxed);
    atomic_thread_fence(memory_order_release);
    for (unsigned i = 0; i < FW_VIEW_WORDS; ++i)
        atomic_store_explicit(&s->view_words[i], w[i], memory_order_relaxed);
    atomic_store_explicit(&s->view_seq, seq + 2u, memory_order_release);
}

void fw_view_read(fw_controller *c)
{
    fw_view_read_into(c, &c->th.view);
}

void fw_view_read_into(fw_controller *c, fw_view *out)
{
    fw_shared *s = &c->sh;
    uint32_t w[FW_VIEW_WORDS];
    for (;;) {
        const uint32_t a = atomic_load_explicit(&s->view_seq, memory_order_acquire);
        if (a & 1u)
            continue; /* the tick is writing (on the host, in another thread) */
        for (unsigned i = 0; i < FW_VIEW_WORDS; ++i)
            w[i] = atomic_load_explicit(&s->view_words[i], memory_order_relaxed);
        atomic_thread_fence(memory_order_acquire);
        if (atomic_load_explicit(&s->view_seq, memory_order_relaxed) == a)
            break;
    }
    memcpy(out, w, sizeof *out);
}

bool fw_ended_post(fw_controller *c, const fw_traj_ended *e)
{
    fw_shared *s = &c->sh;
    const uint32_t in = atomic_load_explicit(&s->ended_in, memory_order_relaxed);
    if (in - atomic_load_explicit(&s->ended_out, memory_order_acquire) >= FW_ENDED_RING)
        return false;
    s->ended[in % FW_ENDED_RING] = *e;
    atomic_store_explicit(&s->ended_in, in + 1u, memory_order_release);
    return true;
}

bool fw_ended_take(fw_controller *c, fw_traj_ended *e)
{
    fw_shared *s = &c->sh;
    const uint32_t out = atomic_load_explicit(&s->ended_out, memory_order_relaxed);
    if (atomic_load_explicit(&s->ended_in, memory_order_acquire) == out)
        return false;
    *e = s->ended[out % FW_ENDED_RING];
    atomic_store_explicit(&s->ended_out, out + 1u, memory_order_release);
    return true;
}
