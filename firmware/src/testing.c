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

int fw_testing_homed_at_home(fw_controller *c)
{
    fw_tick *t = &c->tick;
    tse_ik_result r;
    if (!stepgen_idle(&c->sg) || tse_ik(&t->geom, t->geom.home_pose, NULL, &r) != TSE_OK)
        return -1;
    int32_t steps[6];
    for (int k = 0; k < 6; ++k) {
        t->q[k] = t->q_prev[k] = r.q[k];
        t->pose[k] = t->geom.home_pose[k];
        steps[k] = fw_steps_of(&t->params, r.q[k]);
    }
    stepgen_set_position(&c->sg, steps);
    t->homed = true;
    t->pose_known = true;
    fw_publish(c);
    return 0;
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
