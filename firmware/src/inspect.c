#include "fw/inspect.h"

#include <string.h>

#include "controller_internal.h"

void fw_inspect(const fw_controller *c, fw_inspection *out)
{
    const fw_tick *t = &c->tick;
    const fw_thread *th = &c->th;
    memset(out, 0, sizeof *out);
    out->state = t->state;
    out->fault = t->fault;
    out->pending_fault = t->pending_fault;
    out->homed = t->homed;
    out->drives_on = t->drives_on;
    out->pose_known = t->pose_known;
    for (int k = 0; k < 6; ++k) {
        out->pose[k] = t->pose[k];
        out->q[k] = t->q[k];
    }
    out->params = t->params;
    out->lim = t->lim;

    out->src = t->src;
    out->has_next = t->has_next;
    out->stopping = t->stopping;
    out->tau = t->tau;
    out->stop_t = t->stop_t;
    out->stop_T = t->stop_T;
    out->segments_run = t->segments_run;
    out->blend_k0 = t->blend_k0;
    out->move = t->move;
    out->next = t->next;
    out->joint_T = t->joint.prof.T;
    out->joint_Ta = t->joint.prof.Ta;

    out->home_active = t->home.active;
    out->home_abort = t->home.abort;
    out->home_phase = t->home.phase;
    memcpy(out->home_axis, t->home.axis, sizeof out->home_axis);

    out->traj_depth = fw_traj_queue_depth(&t->traj);
    out->traj_free = fw_traj_queue_free(&t->traj);
    out->traj_end_us = t->traj.end_us;
    out->traj_closed = t->traj.closed;
    for (int k = 0; k < 6; ++k)
        out->traj_tail[k] = th->traj.tail.pose[k];

    out->run_open = t->traj_open;
    out->run_clock = t->traj_clock;
    out->run_id = t->traj_id;
    out->run_next_seq = th->next_seq;
    out->run_rows = t->traj_rows;
    out->run_ended = th->ended;
    out->run_fault = th->ended_fault;
    out->run_ended_id = th->ended_id;
    out->run_ended_rows = th->ended_rows;
    out->run_ended_us = th->ended_us;
    const uint32_t in = atomic_load(&c->sh.ended_in), taken = atomic_load(&c->sh.ended_out);
    out->posted_ends = in - taken;
    if (in != taken) {
        const fw_traj_ended *e = &c->sh.ended[(in - 1u) % FW_ENDED_RING];
        out->posted_how = (fw_traj_end)e->how;
        out->posted_fault = (fw_fault)e->fault;
        out->posted_id = e->id;
        out->posted_rows = e->rows;
        out->posted_us = e->us;
    }

    out->stage_seq = th->stage_seq;
    out->stage_have = th->stage_have;
    memcpy(out->stage_v, th->stage_v, sizeof out->stage_v);
    out->last_seq = th->last_seq;
    out->any_commit = th->any_commit;
    out->heartbeat_us = atomic_load(&c->sh.heartbeat_us);

    out->sg_cfg = c->sg.cfg;
    out->sg_queued = stepgen_queued(&c->sg);
    out->sg_idle = stepgen_idle(&c->sg);
    out->sg_running = c->sg.running;
    stepgen_positions(&c->sg, out->sg_pos);
    out->sg_overruns = c->sg.overruns;
}
