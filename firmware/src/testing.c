#include "fw/testing.h"

#include "controller_internal.h"
#include "publish.h"
#include "steps.h"

int fw_testing_set_positions(fw_controller *c, const int32_t pos[6])
{
    const int rc = stepgen_set_position(&c->sg, pos);
    fw_publish(c);
    return rc;
}

int fw_testing_homed_at(fw_controller *c, const tse_real p[6])
{
    fw_tick *t = &c->tick;
    tse_ik_result r;
    if (!stepgen_idle(&c->sg) || tse_ik(&t->geom, p, NULL, &r) != TSE_OK)
        return -1;
    int32_t steps[6];
    for (int k = 0; k < 6; ++k) {
        t->q[k] = t->q_prev[k] = r.q[k];
        t->pose[k] = p[k];
        steps[k] = fw_steps_of(&t->params, r.q[k]);
    }
    stepgen_set_position(&c->sg, steps);
    t->homed = true;
    t->pose_known = true;
    fw_publish(c);
    return 0;
}

int fw_testing_homed_at_home(fw_controller *c)
{
    return fw_testing_homed_at(c, c->tick.geom.home_pose);
}

void fw_testing_force_param(fw_controller *c, fw_param_id id, int32_t value)
{
    c->tick.params.v[id] = value;
    c->th.params.v[id] = value;
    fw_publish(c);
}

void fw_testing_hold_point(fw_controller *c, const fw_traj_point *p)
{
    fw_traj_queue *q = &c->tick.traj;
    q->dropped = false;
    q->closed = false;
    fw_reason why;
    fw_traj_queue_push(q, p, &why);
    fw_publish(c);
}

void fw_testing_overrun(fw_controller *c)
{
    ++c->sg.overruns;
}
