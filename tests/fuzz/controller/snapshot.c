#include "snapshot.h"

#include <string.h>

void snapshot_take(const rig *r, snapshot *s)
{
    memset(s, 0, sizeof *s);
    fw_inspection *c = &s->in;
    fw_inspect(r->c, c);
    /* Scratch a refusal may overwrite but nothing reads (snapshot.h). */
    if (c->src != FW_SRC_MOVE)
        memset(&c->move, 0, sizeof c->move);
    if (!c->has_next) {
        memset(&c->next, 0, sizeof c->next);
        c->blend_k0 = 0;
    }
    if (!c->stopping)
        c->stop_t = c->stop_T = TSE_R(0.0);
    /* An end the tick posted before the frame came: the frame's poll takes it before it handles
     * the frame (firmware/src/runtime.c), so it is how the last trajectory ended as the frame finds it. */
    if (c->posted_ends) {
        c->run_ended = c->posted_how;
        c->run_fault = c->posted_fault;
        c->run_ended_id = c->posted_id;
        c->run_ended_rows = c->posted_rows;
        c->run_ended_us = c->posted_us;
    }
    c->posted_ends = 0;
    c->posted_how = FW_TRAJ_END_NONE;
    c->posted_fault = FW_FAULT_NONE;
    c->posted_id = 0;
    c->posted_rows = 0;
    c->posted_us = 0;
    if (c->src != FW_SRC_TRAJ) {
        c->traj_end_us = 0;
        c->traj_closed = false;
    }
    s->enable_out = r->f.enabled;
    s->pulse_ns = r->f.pulse_ns;
    s->dir_setup_ns = r->f.dir_setup_ns;
    s->timing_calls = r->f.timing_calls;
    s->storage_len = r->f.storage_len;
    memcpy(s->storage, r->f.storage, sizeof s->storage);
}

#define SAME(field)                                                                                \
    do {                                                                                           \
        if (memcmp(&a->field, &b->field, sizeof a->field) != 0) {                                  \
            *what = #field;                                                                        \
            return false;                                                                          \
        }                                                                                          \
    } while (0)

bool snapshot_same(const snapshot *a, const snapshot *b, bool spent, bool stepped, const char **what)
{
    SAME(in.state);
    SAME(in.fault);
    SAME(in.pending_fault);
    SAME(in.homed);
    SAME(in.drives_on);
    SAME(enable_out);
    SAME(in.pose_known);
    SAME(in.params);
    SAME(in.lim);
    SAME(pulse_ns);
    SAME(dir_setup_ns);
    SAME(timing_calls);
    SAME(storage_len);
    SAME(storage);
    if (!spent) {
        SAME(in.stage_seq);
        SAME(in.stage_have);
        SAME(in.stage_v);
        SAME(in.last_seq);
        SAME(in.any_commit);
    }
    SAME(in.src);
    SAME(in.has_next);
    SAME(in.stopping);
    SAME(in.move.to);
    SAME(in.move.prof.T);
    SAME(in.next.to);
    SAME(in.next.prof.T);
    SAME(in.blend_k0);
    SAME(in.stop_t);
    SAME(in.stop_T);
    SAME(in.tau);
    SAME(in.segments_run);
    SAME(in.traj_depth);
    SAME(in.traj_end_us);
    SAME(in.traj_closed);
    SAME(in.run_open);
    SAME(in.run_clock);
    SAME(in.run_id);
    SAME(in.run_next_seq);
    SAME(in.run_rows);
    SAME(in.run_ended);
    SAME(in.run_fault);
    SAME(in.run_ended_id);
    SAME(in.run_ended_rows);
    SAME(in.run_ended_us);
    SAME(in.home_active);
    SAME(in.home_abort);
    SAME(in.home_phase);
    SAME(in.home_axis);
    SAME(in.sg_cfg);
    if (!stepped) {
        SAME(in.sg_queued);
        SAME(in.sg_idle);
        SAME(in.sg_pos);
    }
    SAME(in.q);
    SAME(in.pose);
    SAME(in.heartbeat_us);
    return true;
}
