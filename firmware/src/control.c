#include "control.h"

#include "handover.h"
#include "motion.h"
#include "publish.h"
#include "state.h"
#include "supervise.h"

void fw_control_run(fw_controller *c)
{
    fw_estop_complete(c);
    fw_handover_take(c);
    fw_supervise(c);
    const fw_state s = c->tick.state;
    if (s != FW_STATE_ESTOP && s != FW_STATE_FAULT && s != FW_STATE_BOOT && fw_motion_tick(c) != FW_MOTION_RUNS)
        fw_state_at_rest(c);
    fw_publish(c);
}
