#include "snapshot.h"

#include <string.h>

void snapshot_take(const rig *r, snapshot *s)
{
    fw_inspection in;
    fw_inspect(r->c, &in);
    const fw_inspection *c = &in;
    memset(s, 0, sizeof *s);
    s->state = c->state;
    s->fault = c->fault;
    s->pending_fault = c->pending_fault;
    s->homed = c->homed;
    s->drives_on = c->drives_on;
    s->enable_out = r->f.enabled;
    s->pose_known = c->pose_known;
    s->params = c->params;
    s->lim = c->lim;
    s->pulse_ns = r->f.pulse_ns;
    s->dir_setup_ns = r->f.dir_setup_ns;
    s->timing_calls = r->f.timing_calls;
    s->storage_len = r->f.storage_len;
    memcpy(s->storage, r->f.storage, sizeof s->storage);
    s->stage_seq = c->stage_seq;
    s->stage_have = c->stage_have;
    memcpy(s->stage_v, c->stage_v, sizeof s->stage_v);
    s->last_seq = c->last_seq;
    s->any_commit = c->any_commit;
    s->src = c->src;
    s->has_next = c->has_next;
    s->stopping = c->stopping;
    if (c->src == FW_SRC_MOVE) {
        memcpy(s->move_to, c->move.to, sizeof s->move_to);
        s->move_T = c->move.prof.T;
    }
    if (c->has_next) {
        memcpy(s->next_to, c->next.to, sizeof s->next_to);
        s->next_T = c->next.prof.T;
        s->blend_k0 = c->blend_k0;
    }
    s->stop_t = c->stopping ? c->stop_t : TSE_R(0.0);
    s->stop_T = c->stopping ? c->stop_T : TSE_R(0.0);
    s->tau = c->tau;
    s->segments_run = c->segments_run;
    s->traj_depth = c->traj_depth;
    if (c->src == FW_SRC_TRAJ) {
        s->traj_end_us = c->traj_end_us;
        s->traj_closed = c->traj_closed;
    }
    s->run_open = c->run_open;
    s->run_clock = c->run_clock;
    s->run_id = c->run_id;
    s->run_next_seq = c->run_next_seq;
    s->run_rows = c->run_rows;
    s->run_ended = c->run_ended;
    s->run_fault = c->run_fault;
    s->run_ended_id = c->run_ended_id;
    s->run_ended_rows = c->run_ended_rows;
    s->run_ended_us = c->run_ended_us;
    s->home_active = c->home_active;
    s->home_abort = c->home_abort;
    s->home_phase = c->home_phase;
    memcpy(s->home_axis, c->home_axis, sizeof s->home_axis);
    s->sg_cfg = c->sg_cfg;
    s->sg_queued = c->sg_queued;
    s->sg_idle = c->sg_idle;
    memcpy(s->sg_pos, c->sg_pos, sizeof s->sg_pos);
    memcpy(s->q, c->q, sizeof s->q);
    memcpy(s->pose, c->pose, sizeof s->pose);
    s->heartbeat_us = c->heartbeat_us;
}

#define SAME(field)                                                                                \
    do {                                                                                           \
        if (memcmp(&a->field, &b->field, sizeof a->field) != 0) {                                  \
            *what = #field;                                                                        \
            return false;                                                                          \
        }                                                                                          \
    } while (0)

bool snapshot_same(const snapshot *a, const snapshot *b, bool spent, const char **what)
{
    SAME(state);
    SAME(fault);
    SAME(pending_fault);
    SAME(homed);
    SAME(drives_on);
    SAME(enable_out);
    SAME(pose_known);
    SAME(params);
    SAME(lim);
    SAME(pulse_ns);
    SAME(dir_setup_ns);
    SAME(timing_calls);
    SAME(storage_len);
    SAME(storage);
    if (!spent) {
        SAME(stage_seq);
        SAME(stage_have);
        SAME(stage_v);
        SAME(last_seq);
        SAME(any_commit);
    }
    SAME(src);
    SAME(has_next);
    SAME(stopping);
    SAME(move_to);
    SAME(move_T);
    SAME(next_to);
    SAME(next_T);
    SAME(blend_k0);
    SAME(stop_t);
    SAME(stop_T);
    SAME(tau);
    SAME(segments_run);
    SAME(traj_depth);
    SAME(traj_end_us);
    SAME(traj_closed);
    SAME(run_open);
    SAME(run_clock);
    SAME(run_id);
    SAME(run_next_seq);
    SAME(run_rows);
    SAME(run_ended);
    SAME(run_fault);
    SAME(run_ended_id);
    SAME(run_ended_rows);
    SAME(run_ended_us);
    SAME(home_active);
    SAME(home_abort);
    SAME(home_phase);
    SAME(home_axis);
    SAME(sg_cfg);
    SAME(sg_queued);
    SAME(sg_idle);
    SAME(sg_pos);
    SAME(q);
    SAME(pose);
    SAME(heartbeat_us);
    return true;
}
